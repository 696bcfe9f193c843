// pipeline registers: the clocks a deeper filter datapath adds (unit configuration `filter.edge_stages`,
// `filter.bilinear_stages`; docs/cycle-model.md, "Datapath depth"). The depths the SystemVerilog
// tops offer, defined once here, and the chain of registers that models the clocks beyond the
// blocks' own.
//
// A datapath's depth is the latency of its SystemVerilog top (the LATENCY of rtl/sv/edge/
// tfu_edge_interp_top.sv, 1 + popcount(CUTS); of rtl/sv/tfu_bilinear_top.sv, 3 + CUT_V), counted
// in the unit from the texel cache's output register, which the edge top's step 0 reads directly
// and which is the bilinear top's input register S1. The model's blocks take one clock each
// (evaluate() pushes its result into its output channel, whose slot is the block's output
// register): edge_median, edge_direction and edge_merge are the 3-clock edge top's three stages;
// filter is one clock after the cache's register, the bilinear top's S2 and S3 in one (a depth of 2,
// which no SV top builds). A deeper datapath is the same blocks followed by depth - (their clocks)
// pipeline registers.
//
//   pipeline_register  one per extra clock: takes one item per cycle, in order, from its input
//                      channel and pushes it unchanged into its output channel (depth channel_depth,
//                      ready registered), like every block boundary of the unit
//
// Ports (per register):
//   in  T  valid/ready;  out  T  valid/ready  (T: Response, the datapath's pixel: id[31:0], rgba[31:0])
// Rate: one item per clock; latency: one clock per register.
//
// Where the registers stand. In the SV they sit inside the datapath (docs/sv-edge.md's steps, the
// bilinear top's vertical lerp); here they follow the datapath's last block. A fully pipelined
// datapath delivers each item `depth` clocks after it takes it whatever the order of its registers, so
// the cycles are the SV top's while the response block takes one pixel per clock. Only the
// footprints that complete a pixel pass them (a blending pixel's level0 and an anisotropic pixel's
// probes but the last are absorbed by the blend unit and the probe accumulator first): that changes
// no pixel's cycle, only how many results the registers can hold while the response block stalls.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "rtl/datapath_depth.hpp"
#include "rtl/kernel/kernel.hpp"
#include "rtl/timing.hpp"

namespace tfu::rtl {

template <typename T>
class PipelineRegister : public sim::Module {
 public:
  PipelineRegister(sim::Simulator& s, std::string name, sim::Channel<T>& i, sim::Channel<T>& o)
      : Module(s, std::move(name)), in_(i), out_(o) {}
  void evaluate() override {
    if (!in_.can_pop() || !out_.can_push()) return;
    out_.push(in_.front());
    in_.pop();
    sim_.progress();
  }
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }

 private:
  sim::Channel<T>& in_;
  sim::Channel<T>& out_;
};

// `count` pipeline registers after channel `in`, named NAME_1 .. NAME_count (their output channels
// too); out() is the last one's output channel (`in` itself when count is 0).
template <typename T>
class PipelineRegisters {
 public:
  PipelineRegisters(sim::Simulator& s, const std::string& name, sim::Channel<T>& in, int count, size_t depth)
      : in_(in) {
    sim::Channel<T>* from = &in;
    for (int k = 1; k <= count; ++k) {
      channels_.push_back(std::make_unique<sim::Channel<T>>(fmt::format("{}_{}", name, k), depth));
      s.add_clocked(channels_.back().get());
      regs_.push_back(
          std::make_unique<PipelineRegister<T>>(s, fmt::format("{}_{}", name, k), *from, *channels_.back()));
      from = channels_.back().get();
    }
    timing.regs.resize(static_cast<size_t>(count));
    for (int k = 0; k < count; ++k) timing.out.emplace_back(depth);
  }
  sim::Channel<T>& out() { return channels_.empty() ? in_ : *channels_.back(); }
  const sim::Channel<T>& out() const { return channels_.empty() ? in_ : *channels_.back(); }
  const std::vector<std::unique_ptr<sim::Channel<T>>>& channels() const { return channels_; }
  void evaluate() {
    for (const std::unique_ptr<PipelineRegister<T>>& r : regs_) r->evaluate();
  }

  // The registers' timing for the recurrence engine, beside PipelineRegister::evaluate(), which
  // moves its input's head when its output has room, one per cycle: an InOrderTiming per register,
  // with a ChannelTimes per output channel. Both change together.
  struct Timing {
    std::vector<InOrderTiming> regs;
    std::vector<ChannelTimes> out;
    // The item pushed into `in` (the chain's input channel) at `pushed` passes every register:
    // the cycle the last one pushes it (`pushed` when there is none).
    [[gnu::always_inline]] int64_t pass(int64_t pushed, ChannelTimes& in) {
      ChannelTimes* from = &in;
      for (size_t k = 0; k < regs.size(); ++k) {
        pushed = regs[k].move(pushed, *from, &out[k]);
        from = &out[k];
      }
      return pushed;
    }
    // The chain's output channel, whose consumer the response block is (`in` when there is none).
    ChannelTimes& last(ChannelTimes& in) { return out.empty() ? in : out.back(); }
  } timing;

 private:
  sim::Channel<T>& in_;
  std::vector<std::unique_ptr<sim::Channel<T>>> channels_;
  std::vector<std::unique_ptr<PipelineRegister<T>>> regs_;
};

}  // namespace tfu::rtl
