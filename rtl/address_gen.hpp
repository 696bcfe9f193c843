// address_gen: level selection (Sampler::lod_info: bias, clamp, GL level rules), then per selected
// level the integer texel coordinates, the 8-bit fractions and the wrap (dp::texel_coord,
// wrap_index / wrap_run of cmodel). One level footprint per cycle: a blending MIPMAP_LINEAR pixel
// takes two cycles.
//
// Ports:
//   in  pixel      PixelReq                                   valid/ready
//   out footprint  FootprintReq: level[3:0], taps, fu[7:0] fv[7:0], blend[8:0], two, second
// Footprints per base filter:
//   NEAREST          1 tap  (floor(s W), floor(t H))
//   LINEAR           4 taps (i0, j0) (i0 + 1, j0) (i0, j0 + 1) (i0 + 1, j0 + 1)
//   CUBIC            T x T taps from (i0 + m0, j0 + m0), m0 = 1 - T/2, row-major
//   EDGE_PRESERVING  the 12-texel cross (tap k = texel C(k+1) of Lee & Jen Eq. 4) around the
//                    centre square (i0, j0)-(i0 + 1, j0 + 1)
#pragma once

#include "cmodel/sampler.hpp"
#include "rtl/unit_ports.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

class AddressGen : public sim::Module {
 public:
  AddressGen(sim::Simulator& s, sim::Channel<PixelReq>& i, sim::Channel<FootprintReq>& o, const Sampler& sm);
  void evaluate() override;
  std::string state() const override;
  bool busy() const { return holding_; }
  // The footprint of (s, t) on `level` (the combinational part of the block), formed in `f`.
  void footprint(FootprintReq& f, uint32_t id, int level, float s, float t) const;

 private:
  sim::Channel<PixelReq>& in_;
  sim::Channel<FootprintReq>& out_;
  const Sampler& smp_;
  bool holding_ = false;
  PixelReq pixel_{};
  LodInfo lod_{};
  int count_ = 0, sent_ = 0;  // footprints of the held pixel (1, or 2 when blending), sent so far
};

}  // namespace tfu::rtl
