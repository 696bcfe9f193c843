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
  // `pixels` and `exit_cycle` have one slot per request (sized by the caller); pixel i lands in
  // slot i when it retires.
  ResponseSink(sim::Simulator& s, sim::Channel<Response>& i, std::vector<Rgba8>& pixels, std::vector<uint64_t>& exit_cycle,
               const std::vector<uint64_t>& accept_cycle)
      : Module(s, "response"), in_(i), pixels_(pixels), exit_(exit_cycle), accept_(accept_cycle) {}
  void evaluate() override {
    if (!in_.can_pop()) return;
    const Response& r = in_.front();
    if (r.id != retired_ || r.id >= pixels_.size())
      throw CheckFailed(fmt::format("response {} out of order (expected {}) at cycle {}", r.id, retired_, sim_.cycle()));
    const uint64_t now = sim_.cycle();
    pixels_[r.id] = r.rgba;
    exit_[r.id] = now;
    const uint64_t lat = now - accept_[r.id];
    if (lat >= latency.size()) latency.resize(lat + 1);
    ++latency[lat];
    ++retired_;
    in_.pop();
    sim_.progress();
  }
  std::string state() const override { return in_.state(); }
  size_t retired() const { return retired_; }  // pixels out so far (ids 0 .. retired - 1)
  std::vector<uint64_t> latency;  // histogram: latency[c] = pixels that took c cycles

 private:
  sim::Channel<Response>& in_;
  std::vector<Rgba8>& pixels_;
  std::vector<uint64_t>& exit_;
  const std::vector<uint64_t>& accept_;
  uint32_t retired_ = 0;
};

}  // namespace tfu::rtl
