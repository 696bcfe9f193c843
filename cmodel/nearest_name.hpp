// "Did you mean ...?": the valid name nearest to a mistyped one, for error lines (unknown commands,
// options, filter modes, enum names). One rule everywhere:
//   * names are compared case-insensitively, with '-' and '_' the same letter and leading dashes
//     dropped ("--Cache_Bytes" ~ "cache-bytes");
//   * the distance is the optimal-string-alignment edit distance (insert, delete, substitute, swap
//     two neighbours: one edit each);
//   * a candidate is near when its distance is at most max(1, shorter length / 3) ("trilinar" ->
//     "trilinear", "rendr" -> "render", "rgb8" -> "rgba8"), or when it shares a word of three or more
//     letters with the input, words split at '-' ("--cache-size" -> "--cache-bytes"), or when the
//     input is a prefix of it of three or more letters ("tri" -> "trilinear");
//   * of the near candidates, the one at the least distance, the first in the given order on a tie.
// Tested: NearestName.* (testbench/test_nearest_name.cpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tfu {

// The edit distance of the rule above (after the normalisation).
int name_distance(std::string_view a, std::string_view b);

// The candidate nearest to `input` by the rule above, as the candidate is spelled; nothing when
// none is near or `input` is itself a candidate.
std::optional<std::string> nearest_name(std::string_view input, const std::vector<std::string>& candidates);

// "did you mean 'X'? " when a candidate is near, else "": the opening of an error line's parenthesis,
// as in "unknown wrap mode 'repat' (did you mean 'repeat'? expected repeat, ...)".
std::string did_you_mean(std::string_view input, const std::vector<std::string>& candidates);

}  // namespace tfu
