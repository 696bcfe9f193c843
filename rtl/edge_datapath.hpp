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
//   edge_median_out     EdgeMedianOut: tag, 12 texels (datapath channels), low[12] x [3:0]
//   edge_direction_out  EdgeDirectionOut: the median stage's output + direction[4:0]
//   out Response: id, rgba[31:0]
#pragma once

#include "cmodel/edge_filter.hpp"
#include "rtl/probe_accumulator.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

struct EdgeMedianOut {
  LevelTag tag;
  std::array<Texel4, lee_jen::kTexels> c{};
  lee_jen::LowIndex low{};
};
struct EdgeDirectionOut {
  EdgeMedianOut median;
  int direction = 0;
};

// The direction-select block as a structure: ROM reads, weighted differences, masked min tree.
// Same result as lee_jen::select_direction (tested exhaustively over shapes and randomly over texels).
lee_jen::EdgeDecision direction_select(const std::array<Texel4, lee_jen::kTexels>& c, const lee_jen::LowIndex& low,
                                       lee_jen::TexelMask shape, uint32_t fu, uint32_t fv, TexelFormat fmt);

class EdgeMedian : public sim::Module {
 public:
  EdgeMedian(sim::Simulator& s, sim::Channel<FilterReq>& i, sim::Channel<EdgeMedianOut>& o)
      : Module(s, "edge_median"), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // The stage's combinational part (evaluate() and the timing recurrences of rtl/unit_recurrence.cpp).
  static void stage(const FilterReq& r, EdgeMedianOut& s);
  // The stage's timing for the recurrence engine, beside evaluate(), which takes its input's head
  // when its output has room, one per cycle: an InOrderTiming (rtl/timing.hpp). Both change together.
  InOrderTiming timing;

 private:
  sim::Channel<FilterReq>& in_;
  sim::Channel<EdgeMedianOut>& out_;
};

class EdgeDirection : public sim::Module {
 public:
  EdgeDirection(sim::Simulator& s, sim::Channel<EdgeMedianOut>& i, sim::Channel<EdgeDirectionOut>& o, size_t textures)
      : Module(s, "edge_direction"), chosen(stat_slots(textures)), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // Histogram of chosen directions per statistics slot (stat_slot(); the total is their sum).
  std::vector<std::array<uint64_t, lee_jen::kDirections>> chosen;
  // The stage's combinational part (and the histogram).
  void stage(const EdgeMedianOut& s, EdgeDirectionOut& o);
  // The stage's timing for the recurrence engine, beside evaluate(), which takes its input's head
  // when its output has room, one per cycle: an InOrderTiming (rtl/timing.hpp). Both change together.
  InOrderTiming timing;

 private:
  sim::Channel<EdgeMedianOut>& in_;
  sim::Channel<EdgeDirectionOut>& out_;
};

class EdgeMerge : public sim::Module {
 public:
  EdgeMerge(sim::Simulator& s, sim::Channel<EdgeDirectionOut>& i, sim::Channel<Response>& o)
      : Module(s, "edge_merge"), in_(i), out_(o) {}
  void evaluate() override;
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // The stage's datapath: true with the pixel's response in `out` when the footprint completes one
  // (LevelTag::emits()).
  bool merge(const EdgeDirectionOut& s, Response& out);
  // Its tail, once the footprint's texel `c` is merged (Eq. 6): the level register, the trilinear
  // blend, the probe accumulator, encode (merge() and edge_stages_fused()).
  bool finish(const LevelTag& tag, Texel4 c, Response& out);
  // The stage's timing for the recurrence engine, beside evaluate(), which takes its input's head,
  // one per cycle, when the response channel has room if the footprint completes a pixel (and at
  // once if not): an InOrderTiming (rtl/timing.hpp) without an output for the others. Both change
  // together.
  InOrderTiming timing;

 private:
  sim::Channel<EdgeDirectionOut>& in_;
  sim::Channel<Response>& out_;
  Texel4 first_{};  // level0 result of a blending pixel (register)
  ProbeAccumulator probes_;  // the probes of an anisotropic pixel (probe_accumulator.hpp)
};

// The three stages' combinational parts in one call (software speed only: the recurrences' edge
// footprints, rtl/unit_recurrence.cpp, unless TFU_PLAIN=1 / --plain): the texels decoded once, the
// medians by lee_jen::median_low_pass and the direction by lee_jen::select_direction (the golden
// model's forms of median_network_eval and direction_select, which equal them:
// MedianNetwork.RandomKeysAllShapesAllOutputs, TfuUnit.DirectionSelectTreeEqualsTheGoldenArgmin),
// the direction histogram and EdgeMerge::finish, with no stage registers copied. Its plain twin:
// EdgeMedian::stage, EdgeDirection::stage, EdgeMerge::merge in turn; its equality test:
// TfuUnit.EdgeFusedStagesEqualThePlainStages. True with the pixel's response in `out` as merge().
bool edge_stages_fused(const FilterReq& r, EdgeDirection& direction, EdgeMerge& merge, Response& out);

}  // namespace tfu::rtl
