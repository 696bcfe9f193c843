// "Did you mean": the rule of cmodel/nearest_name.hpp, and the error lines that use it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"
#include "cmodel/texture.hpp"

namespace tfu {
namespace {

std::string refusal_of(void (*f)()) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(NearestName, DistanceIsTheOptimalStringAlignmentDistanceAfterNormalising) {
  EXPECT_EQ(name_distance("trilinar", "trilinear"), 1);        // one insertion
  EXPECT_EQ(name_distance("rendre", "render"), 1);             // one swap of neighbours
  EXPECT_EQ(name_distance("--Cache_Bytes", "cache-bytes"), 0);  // case, '_' and leading dashes
  EXPECT_EQ(name_distance("abc", ""), 3);
  EXPECT_EQ(name_distance("kitten", "sitting"), 3);             // the textbook pair
  EXPECT_EQ(name_distance("ca", "abc"), 3);                    // OSA, not the unrestricted Damerau distance (2)
}

TEST(NearestName, NearByDistanceSharedWordOrPrefix) {
  const std::vector<std::string> commands{"render", "report", "sample", "sim", "sim-results", "sweep"};
  EXPECT_EQ(nearest_name("rendr", commands).value_or("-"), "render");
  EXPECT_EQ(nearest_name("rpeort", commands).value_or("-"), "report");   // a swap of neighbours
  EXPECT_EQ(nearest_name("results", commands).value_or("-"), "sim-results");  // a shared word
  EXPECT_EQ(nearest_name("swe", commands).value_or("-"), "sweep");      // a prefix of 3 letters
  EXPECT_FALSE(nearest_name("zzz", commands));
  EXPECT_FALSE(nearest_name("", commands));
  EXPECT_FALSE(nearest_name("sim", commands));  // valid: nothing to suggest
  EXPECT_EQ(nearest_name("Sim", commands).value_or("-"), "sim");  // another spelling is distance 0
  // ties go to the first candidate in the given order: "sam" is one edit from both
  EXPECT_EQ(nearest_name("sam", {"sum", "sim"}).value_or("-"), "sum");
  EXPECT_EQ(nearest_name("--cache-size", {"--line-bytes", "--cache-bytes", "--ways"}).value_or("-"), "--cache-bytes");
  // a long or hostile input costs at most 64 x 64 cells and suggests nothing
  EXPECT_FALSE(nearest_name(std::string(100000, 'x'), commands));
  EXPECT_EQ(did_you_mean("rendr", commands), "did you mean 'render'? ");
  EXPECT_EQ(did_you_mean("qqqq", commands), "");
}

TEST(NearestName, ErrorLinesOfNamesSuggestTheNearest) {
  const auto opens = [](const std::string& line, const std::string& start) { return line.substr(0, start.size()) == start; };
  EXPECT_TRUE(opens(refusal_of([] { (void)filter_mode_from_name("trilinar"); }),
                    "unknown filter 'trilinar' (did you mean 'trilinear'? expected one of NEAREST, "));
  EXPECT_TRUE(opens(refusal_of([] { (void)filter_mode_from_name("LINEAR_MIPMAP_LINAER"); }),
                    "unknown filter 'LINEAR_MIPMAP_LINAER' (did you mean 'LINEAR_MIPMAP_LINEAR'? expected"));
  EXPECT_EQ(refusal_of([] { (void)texel_format_from_name("rgb8"); }),
            "unknown texel format 'rgb8' (did you mean 'rgba8'? expected rgba8, l8, vs16x2 or srgba8)");
  // nothing near: the line as before
  EXPECT_EQ(refusal_of([] { (void)texel_format_from_name("png"); }),
            "unknown texel format 'png' (expected rgba8, l8, vs16x2 or srgba8)");
}

}  // namespace
}  // namespace tfu
