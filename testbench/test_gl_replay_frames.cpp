// What the GL replay reports about a game's frame (cmodel/gl_replay.hpp): the sampler override of
// the mipmapped textures (ReplayOptions::min_filter, max_aniso: tfu --gl-min-filter, --gl-max-aniso),
// the per-draw facts and their CSV (DrawFacts, write_draw_table: tfu --draws-out), and the vector
// forms of the immediate-mode calls (the engine's sky box). On a dump from a stand-in for apitrace
// ($TFU_APITRACE), so that no apitrace is needed; every expected value follows from the dump by hand.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/gl_replay.hpp"

namespace tfu::gl {
namespace {

namespace fs = std::filesystem;

// An 8 x 8 frame of four full-screen quads (each 16 quads of 2 x 2, 64 pixels, one texture unit):
//   draw 0  texture 1 (2x2 and 1x1 levels, LINEAR_MIPMAP_NEAREST), the default (identity) projection
//   draw 1  texture 2 (2x2, LINEAR, no MIP levels), a perspective projection, depth range [0, 0.3],
//           the first draw after glLockArraysEXT
//   draw 2  texture 1, the second draw of the locked arrays, given by glVertex3fv
//   draw 3  texture 1 after glUnlockArraysEXT, depth range [1, 1], another modelview (glScalef by 2:
//           x, y and w double, the same coverage), by glTexCoord2fv and glVertex3fv
// The perspective projection (column-major) maps z = -1 to w = 1, so x, y in [-1, 1] cover the viewport.
constexpr const char* kDump =
    "1 glXMakeCurrent(dpy = 0x1, drawable = 2, ctx = 0x3) = True\n"
    "2 glViewport(x = 0, y = 0, width = 8, height = 8)\n"
    "3 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
    "4 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGBA, width = 2, height = 2, border = 0, "
    "format = GL_RGBA, "
    "type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call4.bin\"))\n"
    "5 glTexImage2D(target = GL_TEXTURE_2D, level = 1, internalformat = GL_RGBA, width = 1, height = 1, border = 0, "
    "format = GL_RGBA, "
    "type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call5.bin\"))\n"
    "6 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_LINEAR_MIPMAP_NEAREST)\n"
    "7 glBindTexture(target = GL_TEXTURE_2D, texture = 2)\n"
    "8 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGBA, width = 2, height = 2, border = 0, "
    "format = GL_RGBA, "
    "type = GL_UNSIGNED_BYTE, pixels = blob(\"blob_call8.bin\"))\n"
    "9 glTexParameteri(target = GL_TEXTURE_2D, pname = GL_TEXTURE_MIN_FILTER, param = GL_LINEAR)\n"
    "10 glEnable(cap = GL_TEXTURE_2D)\n"
    "11 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
    "12 glBegin(mode = GL_QUADS)\n"
    "13 glVertex2f(x = -1, y = -1)\n"
    "14 glVertex2f(x = 1, y = -1)\n"
    "15 glVertex2f(x = 1, y = 1)\n"
    "16 glVertex2f(x = -1, y = 1)\n"
    "17 glEnd()\n"
    "18 glMatrixMode(mode = GL_PROJECTION)\n"
    "19 glLoadMatrixf(m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, -0.2, 0})\n"
    "20 glDepthRange(zNear = 0, zFar = 0.3)\n"
    "21 glLockArraysEXT(first = 0, count = 4)\n"
    "22 glBindTexture(target = GL_TEXTURE_2D, texture = 2)\n"
    "23 glBegin(mode = GL_QUADS)\n"
    "24 glVertex3f(x = -1, y = -1, z = -1)\n"
    "25 glVertex3f(x = 1, y = -1, z = -1)\n"
    "26 glVertex3f(x = 1, y = 1, z = -1)\n"
    "27 glVertex3f(x = -1, y = 1, z = -1)\n"
    "28 glEnd()\n"
    "29 glBindTexture(target = GL_TEXTURE_2D, texture = 1)\n"
    "30 glBegin(mode = GL_QUADS)\n"
    "31 glVertex3fv(v = {-1, -1, -1})\n"
    "32 glVertex3fv(v = {1, -1, -1})\n"
    "33 glVertex3fv(v = {1, 1, -1})\n"
    "34 glVertex3fv(v = {-1, 1, -1})\n"
    "35 glEnd()\n"
    "36 glUnlockArraysEXT()\n"
    "37 glDepthRange(zNear = 1, zFar = 1)\n"
    "38 glMatrixMode(mode = GL_MODELVIEW)\n"
    "39 glScalef(x = 2, y = 2, z = 2)\n"
    "40 glBegin(mode = GL_QUADS)\n"
    "41 glTexCoord2fv(v = {0.5, 0.25})\n"
    "42 glVertex3fv(v = {-1, -1, -1})\n"
    "43 glVertex3fv(v = {1, -1, -1})\n"
    "44 glVertex3fv(v = {1, 1, -1})\n"
    "45 glVertex3fv(v = {-1, 1, -1})\n"
    "46 glEnd()\n"
    "47 glXSwapBuffers(dpy = 0x1, drawable = 2)\n";

class ReplayFrames : public ::testing::Test {
 protected:
  fs::path dir_;
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tfu-gl-replay-frames-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "x.trace") << "stand-in trace\n";
    std::ofstream(dir_ / "swaps.txt") << "47 glXSwapBuffers(dpy = 0x1, drawable = 2)\n";
    std::ofstream(dir_ / "dump.txt") << kDump;
    // `dump --grep=...` prints the swaps; `dump --blobs ...` prints the dump and writes its blobs.
    std::ofstream(dir_ / "apitrace")
        << "#!/bin/sh\ncase \"$*\" in\n  *--grep*) cat '" << (dir_ / "swaps.txt").string() << "' ;;\n  *) cat '"
        << (dir_ / "dump.txt").string()
        << "'\n     head -c 16 /dev/zero > blob_call4.bin\n     head -c 4 /dev/zero > blob_call5.bin\n"
           "     head -c 16 /dev/zero > blob_call8.bin\n  ;;\nesac\n";
    fs::permissions(dir_ / "apitrace", fs::perms::owner_all);
    setenv("TFU_APITRACE", (dir_ / "apitrace").c_str(), 1);
  }
  void TearDown() override {
    unsetenv("TFU_APITRACE");
    fs::remove_all(dir_);
  }
  Replay replay(const ReplayOptions& o = {}) const { return replay_frame((dir_ / "x.trace").string(), 0, o); }
  // The sampler descriptor each draw's requests name (every request of a draw names the same one).
  static std::map<uint32_t, SamplerDescriptor> samplers_by_draw(const Replay& r) {
    std::map<uint32_t, SamplerDescriptor> out;
    for (const FragmentQuad& q : r.quads)
      out[q.draw] = r.unit_frame->regs.samplers.at(r.requests.requests.at(q.first_request).sampler);
    return out;
  }
};

TEST_F(ReplayFrames, OverridesOnlyTheMipmappedTexturesSamplers) {
  const auto traced = samplers_by_draw(replay());
  ASSERT_EQ(traced.size(), 4u);
  EXPECT_EQ(traced.at(0).mode.base, BaseFilter::Linear);
  EXPECT_EQ(traced.at(0).mode.mip, MipMode::Nearest);  // GL_LINEAR_MIPMAP_NEAREST as traced
  EXPECT_EQ(traced.at(0).max_aniso, 1);
  EXPECT_EQ(traced.at(1).mode.mip, MipMode::None);  // GL_LINEAR
  ReplayOptions o;
  o.min_filter = "GL_LINEAR_MIPMAP_LINEAR";
  o.max_aniso = 8;
  const auto over = samplers_by_draw(replay(o));
  for (uint32_t d : {0u, 2u, 3u}) {  // texture 1: mipmapped
    EXPECT_EQ(over.at(d).mode.base, BaseFilter::Linear) << d;
    EXPECT_EQ(over.at(d).mode.mip, MipMode::Linear) << d;
    EXPECT_EQ(over.at(d).max_aniso, 8) << d;
  }
  // Texture 2 has no MIP levels: as traced (r_textureMode and anisotropy leave such images alone).
  EXPECT_EQ(over.at(1).mode.base, BaseFilter::Linear);
  EXPECT_EQ(over.at(1).mode.mip, MipMode::None);
  EXPECT_EQ(over.at(1).max_aniso, 1);
  o.min_filter = "GL_NEAREST_MIPMAP_NEAREST";
  o.max_aniso = 0;
  const auto nearest = samplers_by_draw(replay(o));
  EXPECT_EQ(nearest.at(0).mode.base, BaseFilter::Nearest);
  EXPECT_EQ(nearest.at(0).mode.mip, MipMode::Nearest);
  EXPECT_EQ(nearest.at(0).max_aniso, 1);
}

TEST_F(ReplayFrames, RefusesAnOverrideWithoutMipLevelsOrOutOfRange) {
  ReplayOptions o;
  o.min_filter = "GL_LINEAR";
  EXPECT_THROW((void)replay(o), InputError);
  o.min_filter = "GL_LINEAR_MIPMAP_LINEAR";
  o.max_aniso = 17;
  EXPECT_THROW((void)replay(o), InputError);
  o.max_aniso = -1;
  EXPECT_THROW((void)replay(o), InputError);
}

TEST_F(ReplayFrames, DrawFactsAndTheirTable) {
  const Replay r = replay();
  ASSERT_EQ(r.facts.size(), 4u);
  EXPECT_TRUE(r.facts[0].orthographic);  // the identity projection: row 3 is (0, 0, 0, 1)
  EXPECT_FALSE(r.facts[1].orthographic);
  EXPECT_EQ(r.facts[1].depth_far, 0.3);
  EXPECT_EQ(r.facts[0].locked_pass, -1);
  EXPECT_EQ(r.facts[1].locked_pass, 0);
  EXPECT_EQ(r.facts[2].locked_pass, 1);
  EXPECT_EQ(r.facts[3].locked_pass, -1);
  EXPECT_EQ(r.facts[0].modelview, 0u);
  EXPECT_EQ(r.facts[2].modelview, 0u);
  EXPECT_EQ(r.facts[3].modelview, 1u);  // glScalef: a second modelview
  EXPECT_EQ(r.facts[3].gl_textures, std::vector<uint32_t>{1});
  // glTexCoord2fv set unit 0's coordinates for draw 3.
  const FragmentQuad* q3 = nullptr;
  for (const FragmentQuad& q : r.quads)
    if (q.draw == 3 && !q3) q3 = &q;
  ASSERT_NE(q3, nullptr);
  EXPECT_EQ(r.requests.requests[q3->first_request].s, 0.5f);
  EXPECT_EQ(r.requests.requests[q3->first_request].t, 0.25f);
  std::ostringstream csv;
  write_draw_table(r, csv);
  std::istringstream lines(csv.str());
  std::string header, row0, row1, row2, row3;
  std::getline(lines, header), std::getline(lines, row0), std::getline(lines, row1), std::getline(lines, row2),
      std::getline(lines, row3);
  EXPECT_EQ(header,
            "draw,call,stages,gl_textures,min_filters,envs,blend,src,dst,alpha_test,depth_test,depth_func,depth_write,"
            "depth_near,depth_far,"
            "orthographic,modelview,locked_pass,triangles,quads,pixels,requests");
  // Each draw: a quad as two triangles over the whole 8 x 8 viewport, 64 pixels. Their shared edge is
  // the screen's diagonal x + y = 8 (GL's y up), through the corners of 4 of the 16 quads, whose pixels
  // lie on both sides (x + y = 7 and 9): each triangle shades those, 16 + 4 = 20 quads, 80 requests.
  EXPECT_EQ(row0, "0,17,1,1,GL_LINEAR_MIPMAP_NEAREST,modulate,0,GL_ONE,GL_ZERO,0,0,GL_LESS,1,0,1,1,0,-1,2,20,64,80");
  EXPECT_EQ(row1, "1,28,1,2,GL_LINEAR,modulate,0,GL_ONE,GL_ZERO,0,0,GL_LESS,1,0,0.3,0,0,0,2,20,64,80");
  EXPECT_EQ(row2, "2,35,1,1,GL_LINEAR_MIPMAP_NEAREST,modulate,0,GL_ONE,GL_ZERO,0,0,GL_LESS,1,0,0.3,0,0,1,2,20,64,80");
  EXPECT_EQ(row3, "3,46,1,1,GL_LINEAR_MIPMAP_NEAREST,modulate,0,GL_ONE,GL_ZERO,0,0,GL_LESS,1,1,1,0,1,-1,2,20,64,80");
}

}  // namespace
}  // namespace tfu::gl
