// What the analytic truth of a procedural texture measures (cmodel/procedural.hpp). Kept apart from
// procedural.hpp so that its few users (tfu report) do not rebuild with every procedural.
#pragma once

#include <string>

namespace tfu {

// True for a texture source "proc:NAME[:SIZE]" whose levels are not filtered copies of level 0
// (mip_colours, make_mip_colours): its truth is level 0's colour, so a MIP-mapped render's
// difference from the truth measures how far lambda is from level 0, not the filter's error.
bool procedural_truth_is_level0_only(const std::string& source);

}  // namespace tfu
