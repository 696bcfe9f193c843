// filter: texel unpack, then the NEAREST select, the bilinear lerp unit or the cubic datapath
// (tile-weight ROM + tile-weight multipliers, adder tree, normalise and clamp), then the trilinear
// blend and the encode to the texture's word. Calls the golden arithmetic (cmodel/datapath.hpp:
// dp::bilinear_lerp (dp::bilinear_lerp8 on 8-bit words), dp::tile_weights_2d, dp::cubic_accumulate,
// dp::cubic_normalize, dp::level_blend (dp::level_blend8)).
//
// Ports:
//   in  texels    FilterReq: texel words, fu[7:0] fv[7:0], blend[8:0], two, second   valid/ready
//   out response  Response: id[31:0], rgba[31:0]
// Rate: a filter lane is 4 texel multipliers per channel (one bilinear per clock). A level
// footprint of n taps occupies the filter for ceil(n / (4 lanes)) clocks: 1 for bilinear, 4 for a
// 4x4 cubic with one lane, 1 with four lanes.
#pragma once

#include "cmodel/sampler.hpp"
#include "rtl/unit_ports.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

class FilterUnit : public sim::Module {
 public:
  FilterUnit(sim::Simulator& s, sim::Channel<FilterReq>& i, sim::Channel<Response>& o, const Sampler& smp, int lanes);
  void evaluate() override;
  std::string state() const override;
  uint64_t busy_cycles() const { return busy_cycles_; }

 private:
  sim::Channel<FilterReq>& in_;
  sim::Channel<Response>& out_;
  const Sampler& smp_;
  BaseFilter base_;
  TexelFormat fmt_, unpack_fmt_;
  int lanes_;
  int remaining_ = -1;  // clocks left on the current footprint (-1: not started)
  std::array<int, 17> extra_clocks_{};  // per tap count n: ceil(n / (4 lanes)) - 1 (the lane sequencer's decode)
  uint64_t busy_cycles_ = 0;
  Texel4 first_{};  // level0 result of a blending pixel (register)
  // LINEAR on an 8-bit format (RGBA8, L8) runs dp::bilinear_lerp8 / level_blend8 on the texel words:
  // the same units as dp::bilinear_lerp / level_blend + encode (bit-identical, tested), fewer
  // software instructions.
  bool words8_;
  Rgba8 first8_{};  // level0 word of a blending pixel (register)
  Texel4 filter_level(const FilterReq& r) const;
};

}  // namespace tfu::rtl
