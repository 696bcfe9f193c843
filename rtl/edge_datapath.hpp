// The edge-preserving filter datapath (Lee & Jen 2003), fully pipelined: one pixel per clock,
// three registered stages.
//
//   edge_median    texel unpack; RGB->Y (5R + 9G + 2B, shift-and-add); keys Y*16+n; the median
//                  network of compare cells (rtl/median_network.hpp) -> low[n], the texel number of
//                  each Eq. 4 median
//   edge_direction 22 direction-weight ROMs (address (fv>>4)<<4 | fu>>4), weighted differences
//                  w_i * dP_i (Eq. 1-2: 8-bit code x 10-bit dP = 18 bits), usable-direction mask of
//                  the kernel shape, min tree (5 levels, ties to the lower direction index)
//   edge_merge     directional lerp of the low-pass endpoints (Eq. 3), high-frequency bilinear
//                  (Eq. 5), merge and clamp (Eq. 6), trilinear blend, the probe accumulator of an
//                  anisotropic pixel (probe_accumulator.hpp), encode
//
// Ports (between stages, valid/ready channels of depth 2):
//   in  texels  FilterReq: 12 texel words (tap k = C(k+1)), shape[11:0], format[1:0] (each
//               footprint's own texel format), fu fv, blend, blends, is_level1
//   s1  EdgeS1: tag, 12 texels (datapath channels), low[12] x [3:0]
//   s2  EdgeS2: s1 + direction[4:0]
//   out Response: id, rgba[31:0]
#pragma once

#include "cmodel/edge_filter.hpp"
#include "rtl/probe_accumulator.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

struct EdgeS1 {
  LevelTag tag;
  std::array<Texel4, lee_jen::kTexels> c{};
  lee_jen::LowIndex low{};
};
struct EdgeS2 {
  EdgeS1 s1;
  int direction = 0;
};

// The direction-select block as a structure: ROM reads, weighted differences, masked min tree.
// Same result as lee_jen::select_direction (tested exhaustively over shapes and randomly over texels).
lee_jen::EdgeDecision direction_select(const std::array<Texel4, lee_jen::kTexels>& c, const lee_jen::LowIndex& low,
                                       lee_jen::TexelMask shape, uint32_t fu, uint32_t fv, TexelFormat fmt);

class EdgeMedian : public sim::Module {
 public:
  EdgeMedian(sim::Simulator& s, sim::Channel<FilterReq>& i, sim::Channel<EdgeS1>& o)
      : Module(s, "edge_median"), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // The stage's combinational part (evaluate() and the timing recurrences of rtl/unit_recurrence.cpp).
  static void stage(const FilterReq& r, EdgeS1& s);

 private:
  sim::Channel<FilterReq>& in_;
  sim::Channel<EdgeS1>& out_;
};

class EdgeDirection : public sim::Module {
 public:
  EdgeDirection(sim::Simulator& s, sim::Channel<EdgeS1>& i, sim::Channel<EdgeS2>& o)
      : Module(s, "edge_direction"), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  std::array<uint64_t, lee_jen::kDirections> chosen{};  // histogram of chosen directions
  // The stage's combinational part (and the histogram).
  void stage(const EdgeS1& s, EdgeS2& o);

 private:
  sim::Channel<EdgeS1>& in_;
  sim::Channel<EdgeS2>& out_;
};

class EdgeMerge : public sim::Module {
 public:
  EdgeMerge(sim::Simulator& s, sim::Channel<EdgeS2>& i, sim::Channel<Response>& o)
      : Module(s, "edge_merge"), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // The stage's datapath: true with the pixel's response in `out` when the footprint completes one
  // (LevelTag::emits()).
  bool merge(const EdgeS2& s, Response& out);

 private:
  sim::Channel<EdgeS2>& in_;
  sim::Channel<Response>& out_;
  Texel4 first_{};  // level0 result of a blending pixel (register)
  ProbeAccumulator probes_;  // the probes of an anisotropic pixel (probe_accumulator.hpp)
};

}  // namespace tfu::rtl
