// The timing recurrences' LINEAR quad path (software speed only; internal to
// rtl/unit_recurrence.cpp). A quad of four pixels whose sampler is LINEAR without MIP-mapping and
// without clamp-to-border, on an 8-bit texture, takes one level-0 footprint of 2 x 2 taps per
// pixel through the plain blocks. This path forms the same four footprints, looks them up and
// filters them with the blocks' own functions, batched per quad instead of per pixel:
//   address_gen   its per-wrap-pair grid function (AddressGen::grid_function) per pixel, and its
//                 pixel count (the blocks' begin()/issue() sequencer has one footprint to issue);
//   kernel_select nothing (it passes non-edge footprints unchanged);
//   texel_cache   CacheStage::admit_lines per pixel, in pixel order (the tags, the LRU and the
//                 memory queue see the blocks' sequence), then read_square_taps<2>;
//   filter        FilterUnit::filter_linear8x4: the 8-bit lerp of the four pixels in four lanes.
// The timing stays in rtl/unit_recurrence.cpp, shared with the plain path, pixel by pixel. The
// plain path must give the same pixels, cycles and statistics: every test that compares the
// recurrences with the clocked blocks (TfuUnit.*, the differential fuzz target) runs quads through
// both, and TfuUnit.LinearQuadPathEqualsThePlainBlocks compares this path with the plain one.
#pragma once

#include <array>
#include <vector>

#include "rtl/unit_wiring.hpp"

namespace tfu::rtl::detail {

class LinearQuadPath {
 public:
  // `enabled` false: takes() refuses every quad (the plain path alone, for the tests).
  LinearQuadPath(const Registers& regs, Unit& u, bool enabled);
  // The quad goes this way: four pixels, a LINEAR sampler without MIP-mapping whose wrap modes do
  // not clamp to the border, a texture of 8-bit texels (RGBA8, L8).
  bool takes(const QuadReq& q) const {
    return q.npix == 4 && sampler_ok_[q.req.sampler] && texture_ok_[q.req.texture];
  }
  // address_gen: the four pixels' level-0 grids and fractions.
  void address(const QuadReq& q);
  // texel_cache, input side: pixel k's footprint looked up at cycle `now`; the cycle its lines are
  // all in, and the cycles it holds the tag port in `bank_cycles`.
  uint64_t admit(int k, uint64_t now, int& bank_cycles) {
    FootprintResult r;
    return u_.cst.admit_lines(texture_, stage_, 0, footprint_[static_cast<size_t>(k)].grid, now, bank_cycles, r);
  }
  // texel_cache read-out and filter: the four pixels' colours.
  void filter(std::array<Rgba8, 4>& out) const;

 private:
  const Registers& regs_;
  Unit& u_;
  std::vector<bool> sampler_ok_, texture_ok_;
  int texture_ = 0, stage_ = 0;
  // The four pixels' footprints: of each, the fields the grid function writes (grid, fu, fv).
  std::array<FootprintReq, 4> footprint_{};
};

}  // namespace tfu::rtl::detail
