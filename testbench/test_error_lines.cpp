// Error messages and exit codes (the deadlock report included): one line of at most
// 300 characters naming the input, quoted input cut to about 60 characters, JSON errors with file,
// position and key, third-party stderr text carried in our line, the decimal trace number syntax.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "testbench/input_error.hpp"
#include "cmodel/error.hpp"
#include "cmodel/error_report.hpp"
#include "cmodel/json_input.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/stderr_capture.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

// What report_error prints for `e` (into a temporary file) and the exit code it returns.
std::pair<std::string, int> report(std::exception_ptr e) {
  std::FILE* f = std::tmpfile();
  const int code = report_error(e, f);
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += static_cast<char>(c);
  std::fclose(f);
  return {text, code};
}

TEST(ErrorLines, QuotedInputIsCutAndControlCharactersReplaced) {
  EXPECT_EQ(quote_input("short"), "short");
  EXPECT_EQ(quote_input(std::string(60, 'x')), std::string(60, 'x'));
  EXPECT_EQ(quote_input(std::string(61, 'x')), std::string(57, 'x') + "...");
  EXPECT_EQ(quote_input(std::string("a\0b\nc", 5)), "a?b?c");
  // A cut never splits a UTF-8 sequence: "é" is two bytes.
  std::string accents;
  for (int i = 0; i < 40; ++i) accents += "\xc3\xa9";
  const std::string q = quote_input(accents, 10);
  EXPECT_EQ(q, "\xc3\xa9\xc3\xa9\xc3\xa9...");
  EXPECT_EQ(one_line("two\nlines"), "two lines");
  EXPECT_EQ(one_line(std::string(1000, 'm')).size(), kMaxMessageChars);
}

TEST(ErrorLines, EveryExceptionIsOneShortLineWithItsExitCode) {
  const std::string huge(1 << 20, 'k');
  const auto [in_text, in_code] = report(std::make_exception_ptr(InputError(huge + "\nsecond line")));
  EXPECT_EQ(in_code, kExitBadInput);
  EXPECT_EQ(in_text.rfind("tfu: error: kkk", 0), 0u);
  EXPECT_EQ(in_text.find('\n'), in_text.size() - 1);  // exactly one line
  EXPECT_LE(in_text.size() - 1, kMaxLineChars);
  EXPECT_EQ(report(std::make_exception_ptr(CheckFailed("differs"))), std::make_pair(std::string("tfu: check failed: differs\n"), kExitCheckFailed));
  const auto [x_text, x_code] = report(std::make_exception_ptr(std::logic_error("oops")));
  EXPECT_EQ(x_code, kExitInternal);
  EXPECT_EQ(x_text, "tfu: internal error: oops (a bug: please report it)\n");
  const auto [f_text, f_code] =
      report(std::make_exception_ptr(fs::filesystem_error("status", fs::path("/x/y"), std::make_error_code(std::errc::filename_too_long))));
  EXPECT_EQ(f_code, kExitBadInput);
  EXPECT_NE(f_text.find("'/x/y': File name too long"), std::string::npos) << f_text;
}

TEST(ErrorLines, ADeadlockIsOneSummaryLineNamingTheFileWithTheDump) {
  const std::string dump = "cycle 123, last progress at cycle 7: [texel_cache: stuck]" + std::string(5000, '.');
  const auto [text, code] = report(std::make_exception_ptr(DeadlockError(std::string(400, 's'), dump)));
  EXPECT_EQ(code, kExitDeadlock);
  EXPECT_EQ(text.rfind("tfu: deadlock: sss", 0), 0u) << text;
  EXPECT_EQ(text.find('\n'), text.size() - 1);
  EXPECT_LE(text.size() - 1, kMaxLineChars);
  const auto at = text.find("full per-stage dump in ");
  ASSERT_NE(at, std::string::npos) << text;
  const std::string path = text.substr(at + 23, text.find(' ', at + 23) - (at + 23));
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), dump + "\n");
  fs::remove(path);
}

// A 3 MB garbage trace line and a 1 MB unknown scene key are not echoed whole.
TEST(ErrorLines, HugeInputsAreQuotedShortly) {
  std::istringstream trace("0.5,0.5\n" + std::string(3 << 20, 'g') + ",1\n");
  const std::string t = input_error([&] { parse_trace(trace, "big.txt"); });
  EXPECT_EQ(t, "big.txt:2: field 1 '" + std::string(57, 'g') + "...' is not a decimal number");
  const std::string scene = "{\"" + std::string(1 << 20, 'q') + "\": 1, \"meshes\": []}";
  const std::string s = input_error([&] { parse_scene(scene, "big.json"); });
  EXPECT_EQ(s, "big.json: unknown key '" + std::string(57, 'q') + "...'");
}

// Trace numbers: the syntax of docs/traces.md, nothing more (strtof alone takes hex floats and stops at NUL).
TEST(ErrorLines, TraceNumbersAreDecimal) {
  const auto parses = [](const std::string& field) {
    std::istringstream in(field + ",0,0\n");  // a lod trace: one request
    try {
      const Trace t = parse_trace(in, "t");
      return t.requests.size() == 1;
    } catch (const InputError&) {
      return false;
    }
  };
  for (const char* ok : {"0", "-1", "+2.5", ".5", "5.", "1e3", "1E-3", "-2.5e+10", "nan", "NaN", "-inf", "Infinity", "1e99"})
    EXPECT_TRUE(parses(ok)) << ok;
  for (const char* bad : {"0x1p-1", "0X10", "1e", "e3", ".", "-", "1.2.3", "nan(1)", "infx", "1,5", "1 5", "1e+"})
    EXPECT_FALSE(parses(bad)) << bad;
  EXPECT_FALSE(parses(std::string("0.5\0garbage", 11)));
  std::istringstream nul(std::string("0.5\0x,0.5\n", 10));
  EXPECT_EQ(input_error([&] { parse_trace(nul, "n.txt"); }), "n.txt:1: field 1 '0.5?x' is not a decimal number");
}

// JSON numbers out of the range of double, with file, position and key path.
TEST(ErrorLines, JsonErrorsNameFilePositionAndKey) {
  EXPECT_EQ(input_error([] { parse_json_input("{\"memory\": {\"latency\": 1e400}}", "u.json"); }),
            "u.json: line 1, column 28: at memory.latency: number overflow parsing '1e400'");  // its last character
  EXPECT_EQ(input_error([] { parse_json_input("{\"a\": [1, 2, {\"b\": [0, -1e999]}]}", "x.json"); }),
            "x.json: line 1, column 29: at a[2].b[1]: number overflow parsing '-1e999'");
  EXPECT_EQ(input_error([] { parse_json_input("{\n  \"w\": 1,\n  \"h\" 2}", "s.json"); }).rfind("s.json: line 3, column 7: at h: malformed JSON: ", 0),
            0u);
  const std::string deep = std::string(100, '[') + std::string(100, ']');
  EXPECT_EQ(input_error([&] { parse_json_input(deep, "d.json"); }), "d.json: nested deeper than 64 levels");
  EXPECT_EQ(input_error([] { parse_scene("{\"width\": 1e400, \"meshes\": []}", "w.json"); }),
            "w.json: line 1, column 15: at width: number overflow parsing '1e400'");
  // A syntax error inside an array names the element being read.
  EXPECT_EQ(input_error([] { parse_json_input("[1, 2 3]", "a.json"); }).rfind("a.json: line 1, column 7: at [2]: malformed JSON: ", 0), 0u)
      << input_error([] { parse_json_input("[1, 2 3]", "a.json"); });
}

// Every key checked, errors naming the file and the key, values spelled as in the file.
TEST(ErrorLines, ConfigAndSceneValuesAreCheckedAndNamed) {
  EXPECT_EQ(input_error([] { rtl::unit_config_from_json("{\"cache\": {\"ways\": 18446744073709551615}}", "c.json"); }),
            "c.json: 'cache.ways' value 18446744073709551615 is out of range");
  EXPECT_EQ(input_error([] { rtl::unit_config_from_json("{\"cache\": {\"ways\": 2147483647}}", "c.json"); }),
            "c.json: 'cache.ways' 2147483647 must be in 0..1024");
  // The kernel-shape policy is a sampler register now (edge_shape): a bad one names file and key.
  EXPECT_EQ(input_error([] { rtl::unit_config_from_json("{\"shape_policy\": \"static\"}", "c.json"); }),
            "c.json: unknown key 'shape_policy'");
  const std::string mesh =
      R"({"meshes": [{"primitive": "cube", "texture": {"procedural": "checkerboard", "size": 8}, "sampler": SAMPLER}]})";
  const auto with_sampler = [&](const std::string& s) {
    std::string m = mesh;
    m.replace(m.find("SAMPLER"), 7, s);
    return m;
  };
  for (const char* filter : {"linear", "cubic"})
    EXPECT_EQ(input_error([&] { parse_scene(with_sampler(fmt::format(R"({{"filter": "{}", "kernel": "bogus"}})", filter)), "s.json"); })
                  .rfind("s.json: meshes[0].sampler.kernel: unknown kernel 'bogus' (valid: ", 0),
              0u)
        << filter;
  EXPECT_NO_THROW(parse_scene(with_sampler(R"({"filter": "cubic", "kernel": "bspline-interp"})"), "s.json"));
  EXPECT_EQ(input_error([] { parse_scene(R"({"width": 18446744073709551615, "meshes": []})", "s.json"); }),
            "s.json: width: 18446744073709551615 outside 1..8192");
  EXPECT_EQ(input_error([] { parse_scene(R"({"camera": {"position": [0, 0, 1e7]}, "meshes": []})", "s.json"); }),
            "s.json: camera.position: expected finite numbers within +-1e+06, found 10000000.0");
  EXPECT_EQ(input_error([] { parse_scene(R"({"camera": {"fov_y": -1e300}, "meshes": []})", "s.json"); }),
            "s.json: camera.fov_y: expected a finite number within +-1e+06, got -1e+300");
}

// libpng prints "libpng error: ..." on stderr before OpenImageIO fails; our one line carries it
// and nothing reaches stderr.
TEST(ErrorLines, LibpngMessagesAreCarriedInOurLine) {
  const fs::path d = fs::temp_directory_path() / fmt::format("tfu_error_lines_{}", ::getpid());
  fs::create_directories(d);
  const fs::path good = d / "good.png", bad = d / "bad.png";
  save_image(Image(64, 64, Rgba8{10, 20, 30, 255}), good.string(), true);
  {
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream out(bad, std::ios::binary);
    out << bytes.substr(0, bytes.size() / 2);
  }
  // Watch descriptor 2 ourselves (not through StderrCapture, which load_texture uses inside).
  std::fflush(stderr);
  const int saved = ::dup(2);
  std::FILE* watch = std::tmpfile();
  ::dup2(::fileno(watch), 2);
  const std::string msg = input_error([&] { load_texture(bad.string()); });
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::rewind(watch);
  std::string leaked;
  for (int c; (c = std::fgetc(watch)) != EOF;) leaked += static_cast<char>(c);
  std::fclose(watch);
  EXPECT_EQ(leaked, "");
  EXPECT_NE(msg.find("bad.png: cannot decode pixels: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("(libpng error: "), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos);
  fs::remove_all(d);
}

// A texture file with a long name (found by the texture fuzz target's hostile names): OpenImageIO
// repeats the whole path in its error text, which made a 422-character message. The library's text
// names the file "the file" and is cut, and libpng's captured text gets only the room left: the
// message stays within kMaxMessageChars and still starts with the (shortened) path.
TEST(ErrorLines, LongTextureNamesGiveShortLines) {
  const TempDir d("tfu-error-lines");
  const std::string stem(200, 'n');
  const fs::path good = d.path() / "good.png", bad_png = d.path() / (stem + ".png"), bad_jpg = d.path() / (stem + ".jpg");
  save_image(Image(64, 64, Rgba8{10, 20, 30, 255}), good.string(), true);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(bad_png, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::ofstream(bad_jpg, std::ios::binary) << std::string("\xff\xd8\xff\xe0\x00\x10JFIF\x00", 11) << std::string(40, '\x01');
  for (const fs::path& p : {bad_png, bad_jpg}) {
    const std::string msg = input_error([&] { load_texture(p.string()); });
    EXPECT_LE(msg.size(), kMaxMessageChars) << msg;
    EXPECT_FALSE(has_control_characters(msg)) << msg;
    EXPECT_EQ(msg.rfind(quote_path(p.string()) + ": ", 0), 0u) << msg;
    EXPECT_EQ(msg.find(stem), std::string::npos) << msg;  // the full name is not repeated
  }
}

TEST(ErrorLines, StderrCaptureJoinsLinesAndRestoresStderr) {
  std::string got;
  {
    StderrCapture c;
    std::fputs("first\nsecond  \n\n", stderr);
    got = c.text();
  }
  EXPECT_EQ(got, "first; second");
}

}  // namespace
}  // namespace tfu
