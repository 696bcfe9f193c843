// response: in-order retirement of the unit's outputs; records each pixel's exit cycle and its
// latency (exit - accept at request_fifo) in a histogram.
//
// Ports:
//   in  response  Response: id[31:0], rgba[31:0]   valid/ready (always ready)
#pragma once

#include <vector>

#include "cmodel/error.hpp"
#include "rtl/unit_ports.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

class ResponseSink : public sim::Module {
 public:
  ResponseSink(sim::Simulator& s, sim::Channel<Response>& i, std::vector<Rgba8>& p, std::vector<uint64_t>& exit_cycle,
               const std::vector<uint64_t>& accept_cycle)
      : Module(s, "response"), in_(i), pixels_(p), exit_(exit_cycle), accept_(accept_cycle) {}
  void evaluate() override {
    if (!in_.can_pop()) return;
    const Response& r = in_.front();
    if (r.id != pixels_.size())
      throw CheckFailed(fmt::format("response {} out of order (expected {}) at cycle {}", r.id, pixels_.size(), sim_.cycle()));
    pixels_.push_back(r.rgba);
    exit_.push_back(sim_.cycle());
    const uint64_t lat = sim_.cycle() - accept_[r.id];
    if (latency.size() <= lat) latency.resize(lat + 1);
    ++latency[lat];
    in_.pop();
    sim_.progress();
  }
  std::string state() const override { return in_.state(); }
  std::vector<uint64_t> latency;  // histogram: latency[c] = pixels that took c cycles

 private:
  sim::Channel<Response>& in_;
  std::vector<Rgba8>& pixels_;
  std::vector<uint64_t>& exit_;
  const std::vector<uint64_t>& accept_;
};

}  // namespace tfu::rtl
