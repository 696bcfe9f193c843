// filter: texel unpack, then the NEAREST select, the bilinear lerp unit or the cubic datapath
// (tile-weight ROM + tile-weight multipliers, adder tree, normalise and clamp), then the trilinear
// blend (on Q.8 level results: one rounding, dp::level_blend), the probe accumulator of anisotropic pixels (probe_accumulator.hpp: one response per
// pixel, after its last probe) and the encode to the texture's word. Calls the golden arithmetic (cmodel/datapath.hpp:
// dp::bilinear_lerp(_q8), dp::tile_weights_2d, dp::cubic_accumulate, dp::cubic_normalize, dp::level_blend;
// on 8-bit words the fast forms of cmodel/datapath_fast.hpp, dp::fast::bilinear_lerp8(q) and level_blend8q,
// off with the fast-path switch, cmodel/fast_paths.hpp). Every footprint carries its own mode:
// requests of different samplers and textures follow each other freely.
//
// Ports:
//   in  texels     FilterReq: texel words, tag: base[1:0], format[1:0], sampler[7:0],
//                  texture[11:0], fu[7:0] fv[7:0], blend[8:0], blends, is_level1, probes[4:0],
//                  probe[3:0]                                                       valid/ready
//   out response   Response: id[31:0], rgba[31:0]
//   in  registers  sampler descriptor (rom_linear), texture descriptor (content, S, B), the
//                  sampler's weight ROM (weight_rom_bank.hpp)
// Rate: a filter lane is 4 texel multipliers per channel (one bilinear per clock). A level
// footprint of n taps occupies the filter for ceil(n / (4 lanes)) clocks: 1 for bilinear, 4 for a
// 4x4 cubic with one lane, 1 with four lanes.
#pragma once

#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/descriptors.hpp"
#include "rtl/probe_accumulator.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/weight_rom_bank.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class FilterUnit : public sim::Module {
 public:
  FilterUnit(sim::Simulator& s, sim::Channel<FilterReq>& i, sim::Channel<Response>& o, const Registers& regs,
             const WeightRomBank& roms, int lanes);
  void evaluate() override;
  std::string state() const override;
  // Lane-cycles computed, per statistics slot (stat_slot(); the total is their sum).
  const std::vector<uint64_t>& busy_cycles() const { return busy_cycles_; }
  // The block without its handshakes (evaluate() and the timing recurrences of
  // rtl/unit_recurrence.cpp): the clocks a footprint of `ntaps` texels keeps the lanes busy before
  // it leaves (ceil(ntaps / (4 lanes)) - 1), and its filtering, true with the pixel's response in
  // `out` when the footprint completes one (LevelTag::emits()).
  int extra_clocks(int ntaps) const { return extra_clocks_[static_cast<size_t>(ntaps)]; }
  uint64_t& busy_cycles(size_t slot) { return busy_cycles_[slot]; }  // the busy counter of a statistics slot
  bool filter(const FilterReq& r, Response& out);
  // filter()'s LINEAR lerp on 8-bit words (dp::fast::bilinear_lerp8) for four footprints of one level
  // at once (isotropic pixels), lane k the footprint of q's lane k (dp::fast::bilinear_lerp8x4,
  // equal to bilinear_lerp8 per lane): the recurrences' LINEAR quad path.
  static void filter_linear8x4(const dp::fast::Quad8& q, Rgba8* out) { dp::fast::bilinear_lerp8x4(q, out); }
  // filter()'s blend unit on 8-bit words (a blending pixel's level0 and level1 Q.8 results).
  static Rgba8 blend_linear8(dp::fast::Rgba8q level0, dp::fast::Rgba8q level1, int blend) {
    return dp::fast::level_blend8q(level0, level1, blend);
  }
  // filter_linear8x4 of the four pixels on both levels and the blend unit per pixel
  // (dp::fast::bilinear_blend8x4; blend 0 gives level0's lerp): the recurrences' blending quads.
  static void filter_blend_linear8x4(const dp::fast::Quad8& level0, const dp::fast::Quad8& level1, int blend, Rgba8* out) {
    dp::fast::bilinear_blend8x4(level0, level1, {blend, blend, blend, blend}, out);
  }
  // The block's timing for the recurrence engine (rtl/timing.hpp), beside evaluate(), which it
  // restates item by item; the two change together. evaluate() keeps the head footprint in the
  // lanes for extra_clocks(ntaps) cycles (counted in busy_cycles), then pops it in the first cycle
  // in which the response channel has room, if it completes a pixel: an InOrderTiming with that
  // hold.
  class Timing {
   public:
    explicit Timing(FilterUnit& b) : b_(&b) {}
    // The cycle the footprint of `ntaps` texels pushed at `pushed` leaves `in` (`emits`: it
    // completes a pixel, pushed into `out`); its busy cycles count into `busy`: its statistics
    // slot's counter (busy_cycles(slot)), or a batch's, added to the slot's after it (sums).
    [[gnu::always_inline]] int64_t done(int64_t pushed, int ntaps, bool emits, ChannelTimes& in,
                                        const ChannelTimes& out, uint64_t& busy) {
      const int hold = b_->extra_clocks(ntaps);
      busy += static_cast<uint64_t>(hold);
      return stage_.move(pushed, in, emits ? &out : nullptr, hold);
    }

    // The probe quad path's lockstep footprint (rtl/unit_recurrence.cpp, probe_quad, derives it
    // from done above): the previous footprint left at t - 1; step(t) is done of a footprint of no
    // hold that completes no pixel, pushed at t - 1: it leaves `in` at t.
    bool in_step(int64_t t) const { return stage_.last == t - 1; }
    // The LINEAR quad path's (the same with an output, the pixel's response): the cycle the
    // previous footprint left (-1: none).
    int64_t last() const { return stage_.last; }
    [[gnu::always_inline]] void step(int64_t t, ChannelTimes& in) {
      in.pop(t);
      stage_.last = t;
    }

   private:
    FilterUnit* b_;  // a pointer: the recurrences may copy the timing into registers for a batch
    InOrderTiming stage_;
  } timing{*this};

 private:
  sim::Channel<FilterReq>& in_;
  sim::Channel<Response>& out_;
  const Registers& regs_;
  const WeightRomBank& roms_;
  int lanes_;
  bool word_lerps_;  // LINEAR on 8-bit words, the fast path (cmodel/fast_paths.hpp), read once
  int remaining_ = -1;  // clocks left on the current footprint (-1: not started)
  std::array<int, 17> extra_clocks_{};  // per tap count n: ceil(n / (4 lanes)) - 1 (the lane sequencer's decode)
  std::vector<uint64_t> busy_cycles_;   // per statistics slot
  // The level0 result of a blending pixel (register), Q.8 (8 fraction bits, dp::kLevelFracBits):
  // as channels, or as four 16-bit words when LINEAR on an 8-bit format runs
  // dp::fast::bilinear_lerp8q / level_blend8q on the words (the same units as dp::bilinear_lerp_q8 /
  // level_blend + encode, bit-identical and tested; fewer instructions).
  Texel4 first_{};
  dp::fast::Rgba8q first8q_{};
  ProbeAccumulator probes_;  // the probes of an anisotropic pixel (probe_accumulator.hpp)
  Texel4 filter_level(const FilterReq& r, TexelFormat unpack) const;  // Q.8, for the blend unit
};

}  // namespace tfu::rtl
