// address_gen: level selection (select_levels of cmodel/descriptors.hpp: bias, clamp, GL level
// rules, from the request's sampler descriptor and its texture's level count), then per selected
// level the integer texel coordinates, the 8-bit fractions and the wrap (dp::texel_coord,
// wrap_index / wrap_run of cmodel). One level footprint per cycle: a blending MIPMAP_LINEAR pixel
// takes two cycles.
//
// Ports:
//   in  pixel      PixelReq (descriptor indices, s, t, lambda)             valid/ready
//   out footprint  FootprintReq: level[3:0], grid (columns x[4], rows y[4], cols, rows, used cells),
//                  cross, tag: base[1:0], format[1:0], fu[7:0] fv[7:0], blend[8:0], blends, is_level1;
//                  on a block-compressed texture the grid in blocks, blocks (block columns and rows,
//                  each tap's texel in its block: block_grid, rtl/address_gen_blocks.hpp)
//   in  registers  sampler descriptor (filter mode, wraps, LOD bias and clamps), texture descriptor
//                  (size, level count, format, block format), the weight ROM's tap count (CUBIC)
// Footprints per base filter, as a grid of wrapped columns and rows (the cache forms the taps):
//   NEAREST          1 x 1   (floor(s W), floor(t H))
//   LINEAR           2 x 2   columns i0, i0 + 1 and rows j0, j0 + 1
//   CUBIC            T x T   from (i0 + m0, j0 + m0), m0 = 1 - T/2
//   EDGE_PRESERVING  4 x 4 less its corners: the 12-texel cross (tap k = texel C(k+1) of Lee & Jen
//                    Eq. 4), columns and rows -1..2 around the centre square (i0, j0)-(i0 + 1, j0 + 1)
// Under clamp-to-border the cells of a column or row outside the texture (-1) are not `used`:
// they read the border word.
// Anisotropic pixels (PixelReq probes = N > 1, docs/anisotropic.md): the N probes one after the
// other, each its level footprint(s), probe i's offset probe_offset_q16(major, N, i) (probe ROM,
// one 31 x 15-bit multiply per component) brought to each level by dp::probe_offset_on_level and
// added to the centre's coordinate by dp::probe_texel_coord (NEAREST: dp::probe_nearest_tap), the
// golden model's functions; the tag carries probes and probe. On hits: N footprints per pixel (2N
// when blending). Statistics: counter `probes`, histogram `aniso_probes` (pixels per N).
#pragma once

#include <utility>
#include <vector>

#include "cmodel/descriptors.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/weight_rom_bank.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class AddressGen : public sim::Module {
 public:
  AddressGen(sim::Simulator& s, sim::Channel<PixelReq>& i, sim::Channel<FootprintReq>& o, const Registers& regs,
             const WeightRomBank& roms);
  void evaluate() override;
  std::string state() const override;
  bool busy() const { return holding_; }
  // The footprint of (s, t) on `level` (the combinational part of the block), formed in `f`; with
  // `o`, of an anisotropic probe at that offset from (s, t) (Q.8 texels of the level).
  void footprint(FootprintReq& f, const PixelReq& p, int level, const ProbeLevelOffset* o = nullptr) const;
  // The sequencer, without the handshakes: begin() takes a pixel (level selection, probe count);
  // each issue() forms its next level footprint in `f` and returns true with the pixel's last.
  void begin(const PixelReq& p);
  bool issue(FootprintReq& f);
  // The block's timing for the recurrence engine, beside evaluate(), which takes a pixel when it
  // holds none and issues its level footprints one per cycle, the first in the cycle it took the
  // pixel: a SequencerTiming (rtl/timing.hpp), pixels in, footprints out. Both change together.
  SequencerTiming timing;
  // The level selection of a pixel of sampler and texture `req` at `lambda_q8` (Q.8, before bias and
  // clamps): level 0 alone without MIP-mapping, else select_levels.
  LevelPick pick_levels(const RequestTag& req, int32_t lambda_q8) const {
    const SamplerDescriptor& c = regs_.samplers[req.sampler];
    // Without MIP-mapping level 0 alone (GL), whatever lambda.
    return c.mode.mip == MipMode::None ? LevelPick{}
                                       : select_levels(lambda_q8, c, regs_.textures[req.texture].levels - 1);
  }
  // The sequencer's count of `n` isotropic pixels (one probe each), issued without begin() /
  // issue() by the recurrences' quad paths (rtl/unit_recurrence_linear_quads.cpp,
  // unit_recurrence_cubic_quads.cpp), which form their grids through pick_levels() and
  // grid_function() themselves.
  void count_isotropic_pixels(uint64_t n, size_t slot) { probe_hist_[slot][1] += n; }
  // The same for `n` pixels of `probes` probes each (the recurrences' probe quad path,
  // rtl/unit_recurrence_probes.cpp).
  void count_pixels(uint64_t n, int probes, size_t slot) { probe_hist_[slot][static_cast<size_t>(probes)] += n; }
  // Statistics: probes (counter), aniso_probes (histogram of N per pixel, when a sampler is anisotropic), of the
  // run and of one statistics slot (stat_slot()).
  void publish(sim::Stats& st) const;
  void publish_slot(sim::Stats& st, size_t slot) const;
  bool any_anisotropic() const;  // a bound sampler is anisotropic (the histogram is published, for every slot too)
  // The grid of one footprint (taps, fractions, used cells) on a level of w x h texels, with `o`
  // for an anisotropic probe. grid_any forms every filter's grid with the wrap modes read at run
  // time (the plain unit); LINEAR, the edge cross and CUBIC of a 4-tap ROM use one function per
  // pair of wrap modes (fixed_wrap_grid, chosen per sampler at reset, in
  // rtl/address_gen_fixed_grids.cpp; software speed only, equal to grid_any: tested).
  using GridFn = void (*)(const SamplerDescriptor&, int taps, int first_tap, FootprintReq&, int w, int h, float, float,
                          const ProbeLevelOffset*);
  static void grid_any(const SamplerDescriptor& c, int taps, int first_tap, FootprintReq& f, int w, int h, float s, float t,
                       const ProbeLevelOffset* o);
  GridFn grid_function(size_t sampler) const { return decoded_[sampler].grid; }
  // LINEAR's grid of the four pixels of a quad at once, f[k] at (s[k], t[k]) on a level of w x h
  // texels, no probe offset (the LINEAR quad path, rtl/unit_recurrence_linear_quads.cpp). Software
  // speed only: its plain twin is the sampler's grid function (grid_fixed, and grid_any under
  // TFU_PLAIN=1 / --plain, when the quad path is off), called four times, which it equals by
  // construction (the same function, inlined: one call instead of four, the probe offset's tests
  // folded away); TfuUnit.FixedWrapGridsEqualThePlainAddressUnit compares it with grid_any over
  // every wrap pair. Null for a sampler whose grid function is not LINEAR's per-wrap-pair one.
  using QuadGridFn = void (*)(FootprintReq* f, int w, int h, const float* s, const float* t);
  QuadGridFn quad_grid_function(size_t sampler) const { return decoded_[sampler].quad_grid; }

 private:
  sim::Channel<PixelReq>& in_;
  sim::Channel<FootprintReq>& out_;
  const Registers& regs_;
  // The grids with a per-wrap-pair function: LINEAR's 2 x 2, the edge cross, CUBIC's 4 x 4 (T = 4).
  enum class FixedGrid { Linear, Cross, Cubic4 };
  static GridFn fixed_wrap_grid(FixedGrid shape, WrapMode wrap_s, WrapMode wrap_t);
  template <WrapMode kWs, WrapMode kWt, FixedGrid kShape>
  static void grid_fixed(const SamplerDescriptor& c, int taps, int first_tap, FootprintReq& f, int w, int h, float s, float t,
                         const ProbeLevelOffset* o);
  template <FixedGrid kShape, size_t... k>
  static GridFn fixed_grid(size_t wrap_pair, std::index_sequence<k...>);
  static QuadGridFn linear_quad_grid(WrapMode wrap_s, WrapMode wrap_t);
  template <WrapMode kWs, WrapMode kWt>
  static void grid_linear_quad(FootprintReq* f, int w, int h, const float* s, const float* t);
  template <size_t... k>
  static QuadGridFn linear_quad_grid(size_t wrap_pair, std::index_sequence<k...>);
  // The decoded registers of each sampler descriptor (at reset): the grid function of its filter
  // and wrap modes, the weight ROM's tap count and first tap (CUBIC).
  struct SamplerDecode {
    GridFn grid;
    int taps, first_tap;
    QuadGridFn quad_grid;  // LINEAR with a per-wrap-pair grid: its quad form; else null
  };
  std::vector<SamplerDecode> decoded_;
  bool holding_ = false;
  PixelReq pixel_{};
  LevelPick pick_{};
  int count_ = 0, sent_ = 0;  // level footprints of a probe (1, or 2 when blending), sent so far
  int probe_ = 0;             // the held pixel's probe being issued (0..N-1)
  ProbeOffset offset_{};      // its offset (Q.16 level-0 texels)
  std::vector<std::array<uint64_t, kMaxAniso + 1>> probe_hist_;  // per statistics slot: pixels per probe count N
  static void publish_histogram(sim::Stats& st, const std::array<uint64_t, kMaxAniso + 1>& hist, bool with_histogram);
  void next_probe();
};

}  // namespace tfu::rtl
