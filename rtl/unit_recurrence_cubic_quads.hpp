// The timing recurrences' CUBIC quad path (software speed only). Its plain twin is the recurrences'
// per-footprint path through the blocks (rtl/unit_recurrence.cpp); TfuUnit.CubicQuadPathEqualsThePlainBlocks
// (testbench/test_tfu_unit.cpp) holds it equal to that path and to the clocked blocks: pixels,
// response cycles, cycles and the whole statistics file, on random unit configurations. Off with
// the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain) and with
// run_unit_recurrence(..., quad_paths = false).
//
// A quad of four pixels whose sampler is an isotropic CUBIC-family one (CUBIC,
// CUBIC_MIPMAP_NEAREST, CUBIC_MIPMAP_LINEAR) with a 4-tap weight ROM and wrap modes that do not
// clamp to the border, on an uncompressed texture of 8-bit texels (RGBA8, L8; texels or B-spline
// coefficient codes), takes one or two level footprints of 4 x 4 taps per pixel through the plain
// blocks (the quad's pixels share lambda, so they share the levels and the blend weight). This path
// forms the same footprints, looks them up and filters them with the blocks' own functions or
// their tested fast forms, batched per quad instead of per footprint:
//   lod_unit      LodUnit::quad_lod, as the plain path (called by the recurrences);
//   address_gen   its level selection (AddressGen::pick_levels), its per-wrap-pair grid function
//                 (AddressGen::grid_function: the 4 x 4 grid, rtl/address_gen_fixed_grids.cpp) per
//                 pixel and level, and its pixel count;
//   kernel_select nothing (it passes non-edge footprints unchanged);
//   texel_cache   CacheStage::admit_square4 per footprint, in the plain path's order (pixel by
//                 pixel, level0 then level1: the tags, the LRU, the memory queue see the same
//                 sequence), whose TexelCache::access_square4 is access_grid's lookup in closed form
//                 for a grid whose cells are all used (rtl/texel_cache_full_squares.cpp); then
//                 read_square_taps<4>, read_out's form of a full square grid;
//   filter        FilterUnit::filter_level's CUBIC on 8-bit words: the weight stage
//                 (dp::tile_weights_2d, memoized per fraction pair and sampler:
//                 dp::fast::TileWeightMemo), the adder tree and the normalise-and-clamp stage
//                 (dp::fast::cubic_accumulate8 or, for weights below 2^15, its multiply-add form
//                 cubic_accumulate8_narrow; cubic_normalize8, with the texture's
//                 cubic_normalize_registers), then the blend unit per pixel (dp::fast::level_blend8:
//                 level_blend of the two levels' codes; without blending the code itself,
//                 round_level(level_q8(c)) = c). (The plain filter keeps a blending pixel's level0
//                 result in a register until its level1 arrives; here the four wait in an array. No
//                 later footprint reads that register before writing it.)
// The timing stays in rtl/unit_recurrence.cpp, shared with the plain path, footprint by footprint.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "cmodel/cubic_fast.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl::detail {

class CubicQuadPath {
 public:
  // `enabled` false: takes() refuses every quad (the plain path alone, for the tests).
  CubicQuadPath(const Registers& regs, Unit& u, bool enabled);
  // The quad goes this way: four pixels, a sampler and a texture of the header's conditions.
  bool takes(const QuadReq& q) const { return q.npix == 4 && sampler_ok_[q.req.sampler] && texture_ok_[q.req.texture]; }
  static bool takes_texture(const TextureDescriptor& t) {
    return (t.format == TexelFormat::RGBA8 || t.format == TexelFormat::L8) && !t.compressed;
  }
  static bool takes_sampler(const SamplerDescriptor& s, const TileWeightRom* rom) {
    return s.mode.base == BaseFilter::Cubic && !s.anisotropic() && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder && rom != nullptr && rom->taps() == 4;
  }
  // address_gen: the levels of the quad's lambda (`lod`, from the LOD unit) and the four pixels'
  // grids and fractions on each; returns the level footprints per pixel (1, or 2 when blending).
  int address(const QuadReq& q, const AnisoLod& lod);
  // texel_cache, input side: level footprint `n` (0: level0, 1: level1) of pixel k, looked up at
  // cycle `now`; the cycle its lines are all in, and the cycles it holds the tag port in
  // `bank_cycles`.
  uint64_t admit(int k, int n, uint64_t now, int& bank_cycles) {
    const int level = n == 0 ? pick_.level0 : pick_.level1;
    return u_.cache_stage.admit_square4(
        texture_, stage_, level, footprint_[static_cast<size_t>(n)][static_cast<size_t>(k)].grid, now, bank_cycles);
  }
  // texel_cache read-out, filter and blend: the four pixels' colours.
  void filter(std::array<Rgba8, 4>& out);

 private:
  const Registers& regs_;
  Unit& u_;
  std::vector<bool> sampler_ok_, texture_ok_;
  // Per sampler descriptor taken: its weight stage, memoized.
  std::vector<std::unique_ptr<dp::fast::TileWeightMemo>> weights_;
  int texture_ = 0, stage_ = 0, sampler_ = 0;
  LevelPick pick_{};
  dp::CubicNormalize norm_{};  // the quad's normalise registers (its sampler's ROM, its texture)
  // The four pixels' footprints on level0 and level1: of each, the fields the grid function
  // writes (grid, fu, fv).
  std::array<std::array<FootprintReq, 4>, 2> footprint_{};
  // The four pixels' codes on one level (`n`: 0 level0, 1 level1).
  void level_codes(int n, int level, std::array<Rgba8, 4>& out);
};

}  // namespace tfu::rtl::detail
