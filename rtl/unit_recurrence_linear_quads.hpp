// The timing recurrences' LINEAR quad path (software speed only, off with TFU_PLAIN=1 or --plain:
// cmodel/fast_paths.hpp; internal to rtl/unit_recurrence.cpp). A quad of four pixels whose sampler is
// LINEAR, LINEAR_MIPMAP_NEAREST
// or LINEAR_MIPMAP_LINEAR, isotropic (max anisotropy 1) and without clamp-to-border, on an 8-bit
// texture (RGBA8, L8, or block-compressed, whose decoders give RGBA8 words, sRGB-encoded for an
// SRGBA8 texture), takes one or two level
// footprints of 2 x 2 taps per pixel through the plain blocks (the
// quad's pixels share lambda, so they share the levels and the blend weight). This path forms the
// same footprints, looks them up and filters them with the blocks' own functions, batched per
// quad instead of per pixel:
//   lod_unit      LodUnit::quad_lod, as the plain path (called by the recurrences);
//   address_gen   its level selection (AddressGen::pick_levels), its per-wrap-pair grid function
//                 (AddressGen::grid_function) per pixel and level, in its quad form
//                 (AddressGen::quad_grid_function: the four pixels in one call), on a compressed texture the
//                 footprint's block coordinates (block_grid, rtl/address_gen_blocks.hpp, as
//                 AddressGen::footprint forms them), and its pixel count;
//   kernel_select nothing (it passes non-edge footprints unchanged);
//   texel_cache   on an uncompressed texture admit_lines split in two, as the probe quad path
//                 does (rtl/unit_recurrence_probes.hpp): the tags of the quad's footprints
//                 (TexelCache::access_squares, rtl/texel_cache_probe_squares.cpp) at address time in
//                 the plain path's order (pixel by pixel, level0 then level1: the tags, the LRU and
//                 the hints see the same sequence; their state depends on the order of the lookups
//                 only, and nothing else reads it during the quad), with the line counters
//                 (CacheStage::count_lines, summed per level); then per footprint, at its accept
//                 cycle in the timing, CacheStage::lines_ready (the bank cycles and the memory
//                 reads of its missed lines: the memory queue sees the same sequence at the same
//                 cycles); the read-out read_square_taps<2>; on a compressed texture
//                 CacheStage::admit_block_square per footprint (the decoders' jobs need the accept
//                 cycle) and read_block_squares (rtl/cache_stage_block_squares.cpp), which take
//                 those block coordinates as the plain blocks do;
//   filter        FilterUnit::filter_linear8x4: the 8-bit lerp of the four pixels in four lanes;
//                 blending, FilterUnit::filter_blend_linear8x4: the Q.8 lerps of both levels, then
//                 the blend unit per pixel. (The plain filter keeps a blending pixel's level0 Q.8
//                 result in a register until its level1 arrives; here the four wait in lanes. No
//                 later footprint reads that register before writing it.) On a compressed SRGBA8
//                 texture, the plain filter's channel datapath instead (FilterUnit::filter_level's
//                 LINEAR: decode_texel to linear unorm12, dp::bilinear_lerp_q8, then dp::level_blend
//                 or dp::round_level, and encode_texel), per pixel: no 8-bit word lerps for this
//                 format (docs/srgb.md).
// The timing stays in rtl/unit_recurrence.cpp, shared with the plain path, footprint by
// footprint (on register copies of the blocks' timing state, as the probe quad path's, lent over a
// run of consecutive quads of this path: linear_run; a pixel's
// hit in lockstep with its predecessor in one step, derived there). The plain path must give the
// same pixels, cycles and statistics: every test that
// compares the recurrences with the clocked blocks (TfuUnit.*, the differential fuzz target) runs
// quads through both, and TfuUnit.LinearQuadPathEqualsThePlainBlocks compares this path with the
// plain one; CompressedUnit.LinearQuadPathEqualsThePlainBlocks (testbench/test_compressed_unit.cpp)
// does so on compressed textures.
#pragma once

#include <array>
#include <vector>

#include "cmodel/datapath_fast.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl::detail {

class LinearQuadPath {
 public:
  // `enabled` false: takes() refuses every quad (the plain path alone, for the tests).
  LinearQuadPath(const Registers& regs, Unit& u, bool enabled);
  // The quad goes this way: four pixels, an isotropic LINEAR-family sampler whose wrap modes do
  // not clamp to the border, a texture of 8-bit texels (RGBA8, L8, block-compressed).
  bool takes(const QuadReq& q) const { return q.npix == 4 && sampler_ok_[q.req.sampler] && texture_ok_[q.req.texture]; }
  // Its texture and sampler conditions, per descriptor.
  static bool takes_texture(const TextureDescriptor& t) {
    return (t.format == TexelFormat::RGBA8 || t.format == TexelFormat::L8 ||
            (t.format == TexelFormat::SRGBA8 && t.compressed)) &&
           t.content == TextureContent::Texels;
  }
  static bool takes_sampler(const SamplerDescriptor& s) {
    return s.mode.base == BaseFilter::Linear && !s.anisotropic() && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder;
  }
  // address_gen: the levels of the quad's lambda (`lod`, from the LOD unit) and the four pixels'
  // grids and fractions on each; returns the level footprints per pixel (1, or 2 when blending).
  int address(const QuadReq& q, const AnisoLod& lod);
  // texel_cache, input side: level footprint `n` (0: level0, 1: level1) of pixel k, looked up at
  // cycle `now`; the cycle its lines are all in, and the cycles it holds the tag port in
  // `bank_cycles`.
  // Inline in the recurrences' footprint loop, as admit_lines; the compressed branch out of line.
  // (On an uncompressed texture its tags were looked up by address(): only the memory reads need
  // `now`.)
  [[gnu::always_inline]] uint64_t admit(int k, int n, uint64_t now, int& bank_cycles) {
    if (compressed_) [[unlikely]]
      return admit_compressed(k, n, now, bank_cycles);
    const SquareLookup& l = lookup_[static_cast<size_t>(k * levels_ + n)];
    return u_.cache_stage.lines_ready(texture_, l.cycles, l.misses, missed_.data() + l.first_miss, now, bank_cycles);
  }
  // Level footprint `n` of pixel k hits every line in one bank cycle (its tags, looked up by
  // address(); false on a compressed texture, whose lookups wait for admit()).
  bool hits_in_one_cycle(int k, int n) const {
    const SquareLookup& l = lookup_[static_cast<size_t>(k * levels_ + n)];
    return !compressed_ && l.misses == 0 && l.cycles <= 1;
  }
  // texel_cache read-out, filter and blend: the four pixels' colours.
  void filter(std::array<Rgba8, 4>& out) const;

 private:
  const Registers& regs_;
  Unit& u_;
  std::vector<bool> sampler_ok_, texture_ok_;
  int texture_ = 0, stage_ = 0;
  bool compressed_ = false;  // the quad's texture is block-compressed
  bool srgb_ = false;        // ... and SRGBA8: filter_srgb
  LevelPick pick_{};
  // The four pixels' footprints on level0 and level1: of each, the fields the grid function
  // writes (grid, fu, fv).
  std::array<std::array<FootprintReq, 4>, 2> footprint_{};
  // On a compressed texture, the same footprints in blocks (block_grid, rtl/address_gen_blocks.hpp).
  std::array<std::array<TapBlocks, 4>, 2> squares_{};
  // On an uncompressed texture, the tags' answers (look_up(): TexelCache::access_squares) of level
  // footprint n of pixel k at k levels_ + n (the plain order): the bank cycles, the missed lines
  // (at most four of a 2 x 2 footprint) from missed_[first_miss]; look_up()'s batch of grids in
  // the same order (2 x 2, every cell used: only the columns and rows change).
  int levels_ = 1;
  std::array<SquareLookup, 8> lookup_{};
  std::array<TapGrid, 8> grids_{};
  std::array<uint64_t, 8 * 4> missed_{};
  // The tags of the quad's footprints (`levels` per pixel) in the plain path's order, and the
  // cache stage's line counters (their sums per level).
  void look_up(int levels);
  // admit() on a compressed texture: CacheStage::admit_block_square.
  [[gnu::noinline]] uint64_t admit_compressed(int k, int n, uint64_t now, int& bank_cycles);
  // Read-out of the four footprints on one level (`n`: 0 level0, 1 level1) as the lerp unit's
  // lanes (lane k: pixel k).
  void level_taps(int n, int level, dp::fast::Quad8& q) const;
  // filter() on a compressed SRGBA8 texture: the plain filter's channel datapath per pixel.
  void filter_srgb(std::array<Rgba8, 4>& out) const;
  std::array<Texel4, 4> srgb_level(int n, int level) const;  // Q.8, for the blend unit
};

}  // namespace tfu::rtl::detail
