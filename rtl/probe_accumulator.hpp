// probe_accumulator: the register at the end of the filter and of edge_merge that averages the
// probes of an anisotropic pixel (docs/anisotropic.md). Each probe's result (both levels blended)
// arrives in probe order; the register adds w(N, i) c_i per channel (dp::AnisoAccumulator, the
// probe ROM's weights) and, at the last probe, hands out (sum + 128) >> 8: the same unit as the
// golden model's dp::aniso_average. One pixel (N = 1) passes through unchanged.
//
// Ports:
//   in   c[4] (datapath channels of one probe: 8-bit formats 0..255, VS16X2 +-32,640), probes[4:0],
//        probe[3:0] (from the footprint's LevelTag)
//   out  pixel[4] when probe = N - 1
//   reg  acc[4] x 24 bits signed (17 bits suffice for 8-bit channels)
#pragma once

#include "cmodel/aniso.hpp"
#include "rtl/unit_ports.hpp"

namespace tfu::rtl {

class ProbeAccumulator {
 public:
  // Adds probe `tag.probe` of `tag.probes`; true when the pixel is complete, its value in `c`.
  bool add(const LevelTag& tag, Texel4& c) {
    if (tag.probes == 1) return true;
    acc_.add(c, tag.probes, tag.probe + 1);
    if (tag.probe + 1 != tag.probes) return false;
    c = acc_.result();
    acc_.clear();
    return true;
  }

 private:
  dp::AnisoAccumulator acc_;
};

}  // namespace tfu::rtl
