// The timing recurrences' probe quad path (software speed only, off with TFU_PLAIN=1 or --plain:
// cmodel/fast_paths.hpp; internal to rtl/unit_recurrence.cpp). Its plain twin is the plain
// per-footprint path of rtl/unit_recurrence.cpp (AddressGen::begin / issue, CacheStage::
// admit_footprint / read_out_footprint, FilterUnit::filter with its probe accumulator);
// TfuUnit.ProbeQuadPathEqualsThePlainBlocks (testbench/test_tfu_unit.cpp) compares the two,
// and the clocked blocks, over random anisotropic configurations.
//
// A quad of four pixels whose sampler is anisotropic and LINEAR-family (LINEAR_MIPMAP_NEAREST or
// LINEAR_MIPMAP_LINEAR with max anisotropy > 1), without clamp-to-border, on an uncompressed 8-bit
// texture (RGBA8, L8) of texels, takes N probes per pixel (the quad's pixels share the LOD unit's
// result: N, lambda, the major vector, so they share the levels, the blend weight and each probe's
// offset on each level), each probe one level footprint of 2 x 2 taps, or two when blending. This
// path forms the same footprints, looks them up and filters them with the blocks' own units,
// batched per quad instead of per footprint:
//   lod_unit      LodUnit::quad_lod, as the plain path (called by the recurrences);
//   address_gen   its level selection (AddressGen::pick_levels); probe i's offset (probe ROM,
//                 dp::scale_probe_fraction, dp::probe_offset_on_level) once per quad and level in
//                 the fast forms of cmodel/aniso_fast.hpp (equal to the plain units for every
//                 input: AnisoProbes.FastOffsetUnitsEqualThePlainUnits), the centre's Q.8
//                 coordinate (dp::texel_coord) once per pixel and level, the probe's coordinate one
//                 add (dp::probe_texel_coord), the wrap unit with the sampler's modes fixed
//                 (dp::fast::wrap_taps, as AddressGen's per-wrap-pair grids); its probe count;
//   kernel_select nothing (it passes non-edge footprints unchanged);
//   texel_cache   admit_lines split in two: the tags (TexelCache::access_squares, access_square
//                 footprint by footprint with the level's registers read once) of the quad's
//                 footprints in the plain path's order (pixel by pixel, probe by probe, level0 then
//                 level1: the tags and the LRU see the same sequence) at address time, with the
//                 line counters (CacheStage::count_lines, summed per level: sums); then per
//                 footprint, at its accept cycle in the timing, CacheStage::lines_ready (the bank
//                 cycles, the memory reads of its missed lines: the memory queue sees the same
//                 sequence at the same cycles). The tags' state depends on the order of the
//                 lookups only, never on their cycles, and nothing else reads it during the quad;
//                 the read-out read_square_taps' addresses (LevelReadout column, row, at);
//   filter        per probe the four pixels in the four lanes of the lerp unit
//                 (dp::fast::bilinear_lerp8x4_lanes, FilterUnit::filter_linear8x4's unit) or,
//                 blending, of both levels and the blend unit (dp::fast::bilinear_lerp8x4q_lanes
//                 and level_blend8x4_lanes, FilterUnit::filter_blend_linear8x4's), then per pixel
//                 the probe accumulator: dp::AnisoAccumulator's sum of w(N, i) c_i (the probe ROM's
//                 weights; at most 256 x 255, so 16-bit lanes hold it) and (sum + 128) >> 8, which
//                 lies in 0..255, where encode_texel of RGBA8 and L8 is the identity. (The plain
//                 filter keeps a blending probe's level0 Q.8 result in a register and the pixel's
//                 sum in the accumulator; no later footprint reads either before writing it.)
// The texel words come from the texture's memory, not from the cache's state, so the read-out and
// the filter run at address time, before the quad's lookups; the colours wait for the retire.
// The timing stays in rtl/unit_recurrence.cpp, shared with the plain path, footprint by footprint
// (on register copies of the blocks' timing state; a hit in lockstep with its predecessor in one
// step, derived there).
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath_fast.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl::detail {

class ProbeQuadPath {
 public:
  // `enabled` false: takes() refuses every quad (the plain path alone, for the tests).
  ProbeQuadPath(const Registers& regs, Unit& u, bool enabled);
  // The quad goes this way: four pixels, an anisotropic LINEAR-family sampler whose wrap modes do
  // not clamp to the border, an uncompressed texture of 8-bit texels.
  bool takes(const QuadReq& q) const { return q.npix == 4 && sampler_ok_[q.req.sampler] && texture_ok_[q.req.texture]; }
  static bool takes_texture(const TextureDescriptor& t) {
    return byte_channels(t.format) && !t.compressed && t.content == TextureContent::Texels;
  }
  static bool takes_sampler(const SamplerDescriptor& s) {
    return s.mode.base == BaseFilter::Linear && s.anisotropic() && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder;
  }
  // address_gen, the read-out and the filter: the levels of the quad's LOD result `lod`, the
  // footprints of the four pixels' probes, their taps and the pixels' colours; returns the level
  // footprints per pixel (N, or 2N when blending), each pixel's in the plain path's order.
  int address(const QuadReq& q, const AnisoLod& lod);
  // texel_cache, input side: footprint `j` of pixel k (probe j / levels, level j % levels), looked
  // up at cycle `now`; the cycle its lines are all in, and the cycles it holds the tag port in
  // `bank_cycles`. (Its tags were looked up by address(): only the memory reads need `now`.)
  [[gnu::always_inline]] uint64_t admit(int k, int j, uint64_t now, int& bank_cycles) {
    const SquareLookup& l = lookup_[static_cast<size_t>(k)][static_cast<size_t>(j)];
    return u_.cache_stage.lines_ready(texture_, l.cycles, l.misses, missed_.data() + l.first_miss, now, bank_cycles);
  }
  // Footprint `j` of pixel k hits every line in one bank cycle (its tags, looked up by address()).
  bool hits_in_one_cycle(int k, int j) const {
    const SquareLookup& l = lookup_[static_cast<size_t>(k)][static_cast<size_t>(j)];
    return l.misses == 0 && l.cycles <= 1;
  }
  // The four pixels' colours (address() formed them).
  const std::array<Rgba8, 4>& colours() const { return colour_; }

 private:
  static constexpr size_t kFootprints = 2 * kMaxAniso;  // per pixel at most
  Unit& u_;
  const Registers& regs_;
  std::vector<bool> sampler_ok_, texture_ok_;
  int texture_ = 0, stage_ = 0;
  // Per footprint j of a pixel: its level; per pixel and footprint: its grid (2 x 2 taps, every
  // cell used: only the columns and rows change).
  std::array<int, kFootprints> levels_of_{};
  std::array<std::array<TapGrid, kFootprints>, 4> grid_{};
  std::array<Rgba8, 4> colour_{};
  // The tags' answers per pixel and footprint (look_up(): TexelCache::access_squares): the bank
  // cycles, the missed lines (at most four of a 2 x 2 footprint) from missed_[first_miss].
  std::array<std::array<SquareLookup, kFootprints>, 4> lookup_{};
  std::array<uint64_t, 4 * kFootprints * 4> missed_{};
  // The tags of the quad's `footprints` footprints per pixel, in the plain path's order, and the
  // cache stage's line counters (their sums per level).
  void look_up(int footprints, int levels);
  // address() with the sampler's wrap modes fixed (one function per pair, chosen per quad).
  template <WrapMode kWs, WrapMode kWt>
  int probe_footprints(const QuadReq& q, const AnisoLod& lod);
  using ProbeFootprintsFn = int (ProbeQuadPath::*)(const QuadReq&, const AnisoLod&);
  template <size_t... k>
  static ProbeFootprintsFn probe_footprints_fn(size_t wrap_pair, std::index_sequence<k...>);
};

}  // namespace tfu::rtl::detail
