// The GL command stream reader (cmodel/gl_trace.hpp) and the replay's refusals (cmodel/gl_replay.hpp)
// on dumps written by a stand-in for apitrace ($TFU_APITRACE: a shell script that prints a fixed
// dump and writes its blobs), so that these run without apitrace; the real program's trace through
// both models is testbench/gl_replay_test.sh.
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/gl_replay.hpp"
#include "cmodel/gl_trace.hpp"

namespace tfu::gl {
namespace {

namespace fs = std::filesystem;

TEST(GlTrace, ParsesEveryValueKind) {
  const auto c = parse_call_line(
      "70354 glLoadMatrixf(m = {1, 0, 0, 0, 0, 1.777778, 0, 0, 0, 0, -1.007485, -1, 0, 0, -8.029942, 0})", "t");
  ASSERT_TRUE(c);
  EXPECT_EQ(c->number, 70354u);
  EXPECT_EQ(c->name, "glLoadMatrixf");
  const Value& m = c->arg("m", Value::Kind::List);
  ASSERT_EQ(m.list.size(), 16u);
  EXPECT_DOUBLE_EQ(m.list[5], 1.777778);
  EXPECT_DOUBLE_EQ(m.list[14], -8.029942);

  const auto p = parse_call_line(
      "70378 glVertexPointer(size = 3, type = GL_FLOAT, stride = 16, pointer = blob(\"blob_call70378.bin\")) // fake", "t");
  ASSERT_TRUE(p);
  EXPECT_TRUE(p->fake);
  EXPECT_EQ(p->number_arg("size"), 3);
  EXPECT_EQ(p->enum_arg("type"), "GL_FLOAT");
  EXPECT_EQ(p->arg("pointer", Value::Kind::Blob).text, "blob_call70378.bin");

  const auto g = parse_call_line("130 glGetFramebufferAttachmentParameteriv(target = GL_FRAMEBUFFER, pname = GL_X, params = &8)", "t");
  ASSERT_TRUE(g);
  EXPECT_EQ(g->number_arg("params"), 8);  // a reference to one value reads as the value
  EXPECT_FALSE(g->fake);

  // Nested lists, strings with commas and parentheses, and a return value after the call.
  const auto x = parse_call_line(
      "12 glXCreateContext(dpy = 0x55, vis = &{visual = 0x55, depth = 24}, shareList = NULL, direct = True) = 0x558d463516c0", "t");
  ASSERT_TRUE(x);
  ASSERT_EQ(x->args.size(), 4u);
  EXPECT_EQ(x->args[1].second.kind, Value::Kind::Other);
  EXPECT_EQ(x->args[0].second.kind, Value::Kind::Other);  // a pointer is no number
  const auto s = parse_call_line("7 glStringMarkerGREMEDY(len = 4, string = \"a, (b\")", "t");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->args[1].second.text, "\"a, (b\"");
  const auto clear = parse_call_line("9 glClear(mask = GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT)", "t");
  ASSERT_TRUE(clear);
  EXPECT_EQ(clear->args[0].second.text, "GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT");
  EXPECT_EQ(parse_call_line("", "t"), std::nullopt);
  EXPECT_EQ(parse_call_line("// process.name = \"/usr/lib/ioquake3/ioquake3\"", "t"), std::nullopt);
}

TEST(GlTrace, RefusesMalformedLinesNamingThem) {
  // Names are identifiers of at most 64 characters: a fuzzed argument name of 300 bytes 0xff made a
  // later message (a wrong kind of argument, which names it) longer than one line may be.
  const std::string long_arg = "12 glTexImage2D(level = 1, pixel" + std::string(300, '\xff') + "s = blob(16))";
  const std::string long_name = "12 gl" + std::string(300, 'a') + "(cap = GL_BLEND)";
  for (const std::string& bad :
       {std::string("glEnable(cap = GL_BLEND)"), std::string("12 glEnable(cap = GL_BLEND"),
        std::string("12 glEn able(cap = GL_BLEND)"), std::string("12 glEnable(GL_BLEND)"),
        std::string("12345678901234567890 glEnable(cap = GL_BLEND)"), std::string("12 glEnable"), long_arg, long_name,
        std::string("12 glEnable(c-ap = GL_BLEND)"), std::string("12 glEnable( = GL_BLEND)")}) {
    try {
      (void)parse_call_line(bad, "trace.trace: dump line 3");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("trace.trace: dump line 3: ", 0), 0u) << what;
      EXPECT_LE(what.size(), 300u);
    }
  }
  const auto c = parse_call_line("5 glEnable(cap = GL_BLEND)", "t");
  ASSERT_TRUE(c);
  EXPECT_THROW((void)c->number_arg("cap"), InputError);  // an enum is no number
  EXPECT_THROW((void)c->enum_arg("mode"), InputError);   // no such argument
}

// A stand-in for apitrace: `dump --grep=...` prints the swaps, `dump --blobs ...` prints `dump` and
// writes each blob (name, byte count) into its working directory.
class FakeApitrace : public ::testing::Test {
 protected:
  fs::path dir_;
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tfu-gl-trace-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "x.trace") << "stand-in trace\n";
  }
  void TearDown() override {
    unsetenv("TFU_APITRACE");
    fs::remove_all(dir_);
  }
  void install(const std::string& swaps, const std::string& dump, const std::vector<std::pair<std::string, int>>& blobs) {
    std::ofstream(dir_ / "swaps.txt") << swaps;
    std::ofstream(dir_ / "dump.txt") << dump;
    std::string script = "#!/bin/sh\ncase \"$*\" in\n  *--grep*) cat '" + (dir_ / "swaps.txt").string() + "' ;;\n  *) cat '" +
                         (dir_ / "dump.txt").string() + "'\n";
    for (const auto& [name, bytes] : blobs) script += "     head -c " + std::to_string(bytes) + " /dev/zero > " + name + "\n";
    script += "  ;;\nesac\n";
    std::ofstream(dir_ / "apitrace") << script;
    fs::permissions(dir_ / "apitrace", fs::perms::owner_all);
    setenv("TFU_APITRACE", (dir_ / "apitrace").c_str(), 1);
  }
  std::string trace() const { return (dir_ / "x.trace").string(); }
  std::string error_of(int frame) const {
    try {
      (void)replay_frame(trace(), frame);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
};

constexpr const char* kFrameStart =
    "1 glXMakeCurrent(dpy = 0x1, drawable = 2, ctx = 0x3) = True\n"
    "2 glViewport(x = 0, y = 0, width = 8, height = 8)\n";

TEST_F(FakeApitrace, ListsEveryUnsupportedCallAndStateByName) {
  install("9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n",
          std::string(kFrameStart) +
              "3 glEnable(cap = GL_FOG)\n"
              "4 glLineWidth(width = 2)\n"
              "5 glBegin(mode = GL_LINES)\n"
              "6 glEnd()\n"
              "7 glLineWidth(width = 3)\n"
              "9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n",
          {});
  const std::string e = error_of(0);
  // Each name once, with its first call; the enabled fog only where a draw uses it (the glEnd).
  EXPECT_NE(e.find("unsupported GL calls or states: glLineWidth (call 4), glEnable(GL_FOG) (call 6), glBegin(GL_LINES) (call 6)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("x.trace"), std::string::npos) << e;
  EXPECT_LE(e.size(), 300u);
}

TEST_F(FakeApitrace, RefusesAbsurdSizesAndShortBlobs) {
  const std::string upload = "3 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
                             "4 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGBA, width = {}, height = 4, "
                             "border = 0, format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call4.bin\"))\n"
                             "9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n";
  const auto with_width = [&](const std::string& w) {
    std::string u = upload;
    u.replace(u.find("{}"), 2, w);
    return std::string(kFrameStart) + u;
  };
  install("9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n", with_width("4"), {{"blob_call4.bin", 63}});
  EXPECT_NE(error_of(0).find("call 4 glTexImage2D: pixels holds 63 bytes, the call needs 64"), std::string::npos) << error_of(0);
  install("9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n", with_width("1000000"), {{"blob_call4.bin", 64}});
  EXPECT_NE(error_of(0).find("call 4 glTexImage2D: width = 1000000 outside 1.."), std::string::npos) << error_of(0);
  install("9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n", with_width("4"), {{"blob_call4.bin", 64}});
  EXPECT_NE(error_of(1).find("--frame 1 out of range: the trace has 1 frames"), std::string::npos) << error_of(1);
  // The dump ends before the frame does (a truncated trace).
  install("9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n", std::string(kFrameStart), {});
  EXPECT_NE(error_of(0).find("the dump ends before call 9 (the end of frame 0)"), std::string::npos) << error_of(0);
}

// S3TC internal formats: a sub-image must cover whole 4x4 blocks (GL_EXT_texture_compression_s3tc:
// offsets multiples of 4, sizes multiples of 4 or reaching the level's edge), else one line naming
// the call; levels of different internal formats make the texture incomplete (refused by name).
TEST_F(FakeApitrace, S3tcUploadsRefuseSubImagesOffTheBlockGridAndMixedLevels) {
  const std::string upload =
      "3 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
      "4 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_COMPRESSED_RGB_S3TC_DXT1_EXT, "
      "width = 7, height = 8, border = 0, format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = "
      "blob(\"blob_call4.bin\"))\n";
  const auto sub = [&](int x, int y, int w, int h) {
    return std::string(kFrameStart) + upload +
           fmt::format(
               "5 glTexSubImage2D(target = GL_TEXTURE_2D, level = 0, xoffset = {}, yoffset = {}, width = {}, height = "
               "{}, "
               "format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call5.bin\"))\n"
               "9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n",
               x, y, w, h);
  };
  const std::string swaps = "9 glXSwapBuffers(dpy = 0x1, drawable = 2)\n";
  const std::vector<std::pair<std::string, int>> blobs{{"blob_call4.bin", 7 * 8 * 4}, {"blob_call5.bin", 128}};
  // Whole blocks: aligned 4x4, and 3 columns reaching the right edge of the 7-wide level.
  for (const auto& [x, y, w, h] : {std::array{0, 4, 4, 4}, std::array{4, 0, 3, 4}, std::array{0, 0, 4, 8}}) {
    install(swaps, sub(x, y, w, h), blobs);
    EXPECT_EQ(error_of(0), "(no error)") << x << "," << y << " " << w << "x" << h;
  }
  for (const auto& [x, y, w, h] :
       {std::array{2, 0, 4, 4}, std::array{0, 1, 4, 4}, std::array{0, 0, 3, 4}, std::array{4, 4, 3, 3}}) {
    install(swaps, sub(x, y, w, h), blobs);
    const std::string e = error_of(0);
    EXPECT_NE(e.find(fmt::format("call 5 glTexSubImage2D: the rectangle {}x{} at ({}, {}) of level 0 (7x8, "
                                 "GL_COMPRESSED_RGB_S3TC_DXT1_EXT) is not made of whole 4x4 blocks",
                                 w, h, x, y)),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("x.trace"), std::string::npos) << e;
    EXPECT_LE(e.size(), 300u) << e;
  }
  // Level 0 DXT5, level 1 RGBA, sampled mipmapped by a draw: incomplete, refused by name.
  install("19 glXSwapBuffers(dpy = 0x1, drawable = 2)\n",
          std::string(kFrameStart) +
              "3 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
              "4 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, "
              "width = 2, "
              "height = 2, border = 0, format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call4.bin\"))\n"
              "5 glTexImage2D(target = GL_TEXTURE_2D, level = 1, internalformat = GL_RGBA, width = 1, height = 1, "
              "border = 0, "
              "format = GL_RGBA, type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call5.bin\"))\n"
              "6 glEnable(cap = GL_TEXTURE_2D)\n"
              "7 glBegin(mode = GL_TRIANGLES)\n"
              "8 glVertex2f(x = 0, y = 0)\n"
              "10 glVertex2f(x = 1, y = 0)\n"
              "11 glVertex2f(x = 0, y = 1)\n"
              "12 glEnd()\n"
              "19 glXSwapBuffers(dpy = 0x1, drawable = 2)\n",
          {{"blob_call4.bin", 16}, {"blob_call5.bin", 4}});
  const std::string e = error_of(0);
  EXPECT_NE(
      e.find(
          "unsupported GL calls or states: texture 1 with levels of different internal formats (incomplete) (call 12)"),
      std::string::npos)
      << e;
}

TEST_F(FakeApitrace, NamesAMissingApitrace) {
  setenv("TFU_APITRACE", (dir_ / "no-such-apitrace").c_str(), 1);
  const std::string e = error_of(0);
  EXPECT_NE(e.find("cannot run"), std::string::npos) << e;
  EXPECT_NE(e.find("Debian package apitrace"), std::string::npos) << e;
}

}  // namespace
}  // namespace tfu::gl
