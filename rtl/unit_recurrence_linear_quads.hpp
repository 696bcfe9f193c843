// The timing recurrences' LINEAR quad path (software speed only, off with TFU_PLAIN=1 or --plain:
// cmodel/fast_paths.hpp; internal to rtl/unit_recurrence.cpp). A quad of four pixels whose sampler is
// LINEAR, LINEAR_MIPMAP_NEAREST
// or LINEAR_MIPMAP_LINEAR, isotropic (max anisotropy 1) and without clamp-to-border, on an 8-bit
// texture, takes one or two level footprints of 2 x 2 taps per pixel through the plain blocks (the
// quad's pixels share lambda, so they share the levels and the blend weight). This path forms the
// same footprints, looks them up and filters them with the blocks' own functions, batched per
// quad instead of per pixel:
//   lod_unit      LodUnit::quad_lod, as the plain path (called by the recurrences);
//   address_gen   its level selection (AddressGen::pick_levels), its per-wrap-pair grid function
//                 (AddressGen::grid_function) per pixel and level, and its pixel count;
//   kernel_select nothing (it passes non-edge footprints unchanged);
//   texel_cache   CacheStage::admit_lines per footprint, in the plain path's order (pixel by pixel,
//                 level0 then level1: the tags, the LRU and the memory queue see the same
//                 sequence), then read_square_taps<2>;
//   filter        FilterUnit::filter_linear8x4: the 8-bit lerp of the four pixels in four lanes,
//                 per level, then the blend unit (dp::fast::level_blend8) per pixel. (The plain filter
//                 keeps a blending pixel's level0 colour in a register until its level1 arrives;
//                 here the four level0 colours wait in lanes. No later footprint reads that
//                 register before writing it.)
// The timing stays in rtl/unit_recurrence.cpp, shared with the plain path, footprint by
// footprint. The plain path must give the same pixels, cycles and statistics: every test that
// compares the recurrences with the clocked blocks (TfuUnit.*, the differential fuzz target) runs
// quads through both, and TfuUnit.LinearQuadPathEqualsThePlainBlocks compares this path with the
// plain one.
#pragma once

#include <array>
#include <vector>

#include "rtl/unit_wiring.hpp"

namespace tfu::rtl::detail {

class LinearQuadPath {
 public:
  // `enabled` false: takes() refuses every quad (the plain path alone, for the tests).
  LinearQuadPath(const Registers& regs, Unit& u, bool enabled);
  // The quad goes this way: four pixels, an isotropic LINEAR-family sampler whose wrap modes do
  // not clamp to the border, a texture of 8-bit texels (RGBA8, L8) not block-compressed.
  bool takes(const QuadReq& q) const { return q.npix == 4 && sampler_ok_[q.req.sampler] && texture_ok_[q.req.texture]; }
  // address_gen: the levels of the quad's lambda (`lod`, from the LOD unit) and the four pixels'
  // grids and fractions on each; returns the level footprints per pixel (1, or 2 when blending).
  int address(const QuadReq& q, const AnisoLod& lod);
  // texel_cache, input side: level footprint `n` (0: level0, 1: level1) of pixel k, looked up at
  // cycle `now`; the cycle its lines are all in, and the cycles it holds the tag port in
  // `bank_cycles`.
  uint64_t admit(int k, int n, uint64_t now, int& bank_cycles) {
    FootprintResult r;
    return u_.cache_stage.admit_lines(texture_, stage_, n == 0 ? pick_.level0 : pick_.level1,
                              footprint_[static_cast<size_t>(n)][static_cast<size_t>(k)].grid, now, bank_cycles, r);
  }
  // texel_cache read-out, filter and blend: the four pixels' colours.
  void filter(std::array<Rgba8, 4>& out) const;

 private:
  const Registers& regs_;
  Unit& u_;
  std::vector<bool> sampler_ok_, texture_ok_;
  int texture_ = 0, stage_ = 0;
  LevelPick pick_{};
  // The four pixels' footprints on level0 and level1: of each, the fields the grid function
  // writes (grid, fu, fv).
  std::array<std::array<FootprintReq, 4>, 2> footprint_{};
  // Read-out and lerp of the four footprints on one level.
  void lerp_level(const std::array<FootprintReq, 4>& f, int level, Rgba8* out) const;
};

}  // namespace tfu::rtl::detail
