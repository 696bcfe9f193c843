// MIP generation (Lee & Jen Eq. 7-8, Gaussian) and the request-trace format.
#include <cmath>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/trace.hpp"

namespace tfu {
namespace {

TEST(Mipmap, SizeRuleAndLevelCount) {
  EXPECT_EQ(mip_level_count(1, 1), 1);
  EXPECT_EQ(mip_level_count(5, 3), 3);  // 5x3 -> 2x1 -> 1x1
  EXPECT_EQ(mip_level_count(1024, 1), 11);
  EXPECT_EQ(mip_extent(5, 1), 2);
  EXPECT_EQ(mip_extent(5, 7), 1);
  Texture t;
  t.levels.emplace_back(5, 3, Rgba8{9, 9, 9, 9});
  generate_mipmaps(t, MipMethod::Box);
  ASSERT_EQ(t.levels.size(), 3u);
  EXPECT_EQ(t.levels[1].width, 2);
  EXPECT_EQ(t.levels[1].height, 1);
  t.validate("t");
}

TEST(Mipmap, BoxRoundsHalfUp) {
  Image src(2, 2);
  src.texels = {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}, {4, 1, 0, 0}};
  const Image d = downsample(src, TexelFormat::RGBA8, MipMethod::Box, 0);
  EXPECT_EQ(d.at(0, 0).r, 3);  // (1 + 2 + 3 + 4 + 2) >> 2 = 3 (2.5 -> 3)
  EXPECT_EQ(d.at(0, 0).g, 0);  // (1 + 2) >> 2 = 0
  Image row(2, 1);
  row.texels = {{1, 0, 0, 0}, {2, 0, 0, 0}};
  EXPECT_EQ(downsample(row, TexelFormat::RGBA8, MipMethod::Box, 0).at(0, 0).r, 2);  // (1 + 2 + 1) >> 1
}

TEST(Mipmap, GaussianAndEdgeKeepConstants) {
  Image src(8, 6, Rgba8{17, 250, 3, 128});
  for (MipMethod m : {MipMethod::Box, MipMethod::Gaussian, MipMethod::Edge}) {
    const Image d = downsample(src, TexelFormat::RGBA8, m, 128);
    for (const Rgba8& t : d.texels) EXPECT_EQ(t, (Rgba8{17, 250, 3, 128})) << mip_method_name(m);
  }
}

TEST(Mipmap, EdgeAlphaZeroIsBoxAndAlphaOneKeepsEdges) {
  // Vertical edge at an odd position: box averages it to grey, the edge-preserving I keeps a side.
  Image src(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) src.at(x, y) = x < 3 ? Rgba8{0, 0, 0, 255} : Rgba8{255, 255, 255, 255};
  const Image box = downsample(src, TexelFormat::RGBA8, MipMethod::Box, 0);
  const Image e0 = downsample(src, TexelFormat::RGBA8, MipMethod::Edge, 0);
  EXPECT_EQ(box.texels, e0.texels);
  EXPECT_EQ(box.at(1, 2).r, 128);  // texels 2 and 3: (0 + 255 + 0 + 255 + 2) >> 2
  const Image e1 = downsample(src, TexelFormat::RGBA8, MipMethod::Edge, 256);
  EXPECT_TRUE(e1.at(1, 2).r == 0 || e1.at(1, 2).r == 255) << int{e1.at(1, 2).r};
}

TEST(Trace, ParsesEveryModeAndRoundTrips) {
  std::istringstream lod("# comment\n0.5, 0.25, 1.5\n\n1,2,-3\n");
  const Trace a = parse_trace(lod, "a");
  EXPECT_EQ(a.mode, TraceMode::Lod);
  ASSERT_EQ(a.requests.size(), 2u);
  EXPECT_EQ(a.requests[0].lod, 1.5f);
  std::istringstream grad("0,0,0.1,0,0,0.1\n");
  EXPECT_EQ(parse_trace(grad, "g").mode, TraceMode::Grad);
  std::istringstream quad("# tfu-trace mode=quad\n0,0\n0.1,0\n0,0.1\n0.1,0.1\n");
  const Trace q = parse_trace(quad, "q");
  EXPECT_EQ(q.mode, TraceMode::Quad);
  std::ostringstream out;
  write_trace(out, q);
  std::istringstream back(out.str());
  const Trace q2 = parse_trace(back, "q2");
  ASSERT_EQ(q2.requests.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(q2.requests[i].s, q.requests[i].s);
    EXPECT_EQ(q2.requests[i].t, q.requests[i].t);
  }
  std::istringstream nan("nan,inf,0\n");
  EXPECT_TRUE(std::isnan(parse_trace(nan, "n").requests[0].s));
}

TEST(Trace, ErrorsNameFileAndLine) {
  const auto msg = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_trace(in, "f.txt");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(msg("0,0,1\n0,0\n").find("f.txt:2"), std::string::npos);
  EXPECT_NE(msg("0,x,1\n").find("f.txt:1: field 2 'x' is not a decimal number"), std::string::npos);
  EXPECT_NE(msg("0,0\n0,0\n0,0\n").find("not a multiple of 4"), std::string::npos);
  EXPECT_NE(msg("1,2,3,4\n").find("4 fields"), std::string::npos);
  EXPECT_NE(msg("1,,3\n").find("empty field"), std::string::npos);
}

// Randomized fuzz of the trace parser: mutated valid traces either parse or raise InputError with
// a message naming the input; nothing else (no crash, no other exception type, no hang).
TEST(Trace, RandomizedFuzzNeverCrashes) {
  const std::vector<std::string> seeds{"# tfu-trace mode=quad\n0,0\n0.1,0\n0,0.1\n0.1,0.1\n",
                                       "0.5,0.25,1.5\n1,2,-3\n", "0,0,0.1,0,0,0.1\n", "nan,inf,-inf\n"};
  const std::string alphabet = "0123456789.,-+eE#\n \tnaif";
  std::mt19937 rng(1234);
  int parsed = 0, rejected = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    std::string text = seeds[rng() % seeds.size()];
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int e = 0; e < edits; ++e) {
      const size_t pos = text.empty() ? 0 : rng() % (text.size() + 1);
      switch (rng() % 3) {
        case 0: text.insert(pos, 1, alphabet[rng() % alphabet.size()]); break;
        case 1: if (pos < text.size()) text.erase(pos, 1); break;
        default: if (pos < text.size()) text[pos] = static_cast<char>(rng() % 256); break;
      }
    }
    std::istringstream in(text);
    try {
      const Trace t = parse_trace(in, "fuzz");
      if (t.mode == TraceMode::Quad) {
        ASSERT_EQ(t.requests.size() % 4, 0u);
      }
      ++parsed;
    } catch (const InputError& e) {
      ASSERT_EQ(std::string(e.what()).rfind("fuzz", 0), 0u) << e.what();
      ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      ++rejected;
    }
  }
  EXPECT_GT(parsed, 100);
  EXPECT_GT(rejected, 100);
}

}  // namespace
}  // namespace tfu
