// response: in-order retirement of the unit's outputs. Two paths deliver pixels, the filter
// (NEAREST / LINEAR / CUBIC) and the edge-preserving pipeline, each in request order; the sink takes
// the next pixel in request order from whichever path holds it (a two-input in-order merge: the
// texel_cache stage sends footprints down the paths in order, so the pixel due next is at the head
// of one of them). Records each pixel's exit cycle and its latency (exit - accept at request_fifo)
// in a histogram.
//
// Ports:
//   in  filter  Response: id[31:0], rgba[31:0]   valid/ready
//   in  edge    Response: id[31:0], rgba[31:0]   valid/ready
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "cmodel/error.hpp"
#include "rtl/request_stream.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class ResponseSink : public sim::Module {
 public:
  // `pixels` and `exit_cycle` have a slot per request (the whole trace or a window of it,
  // rtl/request_stream.hpp); pixel i lands in slot i when it retires. `trace` says which ids exist.
  ResponseSink(sim::Simulator& s, sim::Channel<Response>& filter, sim::Channel<Response>& edge, RequestRing<Rgba8>& pixels,
               RequestRing<uint64_t>& exit_cycle, const RequestRing<uint64_t>& accept_cycle, const RequestStream& trace)
      : Module(s, "response"), filter_(filter), edge_(edge), pixels_(pixels), exit_(exit_cycle), accept_(accept_cycle),
        trace_(trace) {}
  void evaluate() override {
    sim::Channel<Response>* in = nullptr;
    if (filter_.can_pop() && filter_.front().id == retired_) in = &filter_;
    else if (edge_.can_pop() && edge_.front().id == retired_) in = &edge_;
    if (!in) {
      const bool stuck = (filter_.can_pop() && filter_.front().id < retired_) || (edge_.can_pop() && edge_.front().id < retired_);
      if (stuck) throw CheckFailed(fmt::format("response out of order (expected {}) at cycle {}", retired_, sim_.cycle()));
      return;
    }
    retire(in->front(), sim_.cycle());
    in->pop();
    sim_.progress();
  }
  // Pixel r.id leaves the unit at cycle `now` (its colour, exit cycle and latency recorded).
  [[gnu::always_inline]] void retire(const Response& r, uint64_t now) {
    if (r.id >= trace_.produced()) [[unlikely]]
      beyond_trace(r.id, now);
    pixels_[r.id] = r.rgba;
    exit_[r.id] = now;
    const uint64_t lat = now - accept_[r.id];
    if (lat >= latency.size()) [[unlikely]]
      latency.resize(lat + 1);
    ++latency[lat];
    ++retired_;
  }
  // retire() of the four pixels id .. id + 3 of a quad at cycles now[0..3] (the LINEAR quad path):
  // one look at the trace's length for the four (an atomic load, after which the compiler reloads
  // every record's storage), the same records. Software speed only.
  [[gnu::always_inline]] void retire_quad(uint32_t id, const std::array<Rgba8, 4>& rgba,
                                          const std::array<int64_t, 4>& now) {
    if (id + 3 >= trace_.produced()) [[unlikely]] {
      for (uint32_t k = 0; k < 4; ++k) retire({id + k, rgba[k]}, static_cast<uint64_t>(now[k]));
      return;
    }
    for (uint32_t k = 0; k < 4; ++k) {
      const auto t = static_cast<uint64_t>(now[k]);
      pixels_[id + k] = rgba[k];
      exit_[id + k] = t;
      const uint64_t lat = t - accept_[id + k];
      if (lat >= latency.size()) [[unlikely]]
        latency.resize(lat + 1);
      ++latency[lat];
    }
    retired_ += 4;
  }
  std::string state() const override { return fmt::format("{}, {}, next {}", filter_.state(), edge_.state(), retired_); }
  size_t retired() const { return retired_; }  // pixels out so far (ids 0 .. retired - 1)
  std::vector<uint64_t> latency;  // histogram: latency[c] = pixels that took c cycles

  // The block's timing for the recurrence engine, beside evaluate(), which retires the pixel due
  // next, one per cycle, the cycle after its path's channel made it visible: pixel j retires at
  // max(pushed + 1, retire of pixel j - 1 + 1), and since the paths deliver in id order, taking the
  // pixels in id order gives their retire cycles. An InOrderTiming (rtl/timing.hpp) without an
  // output, over both inputs. Both change together.
  struct Timing {
    InOrderTiming stage;
    // The cycle a pixel pushed at `pushed` into the response channel `in` retires (and leaves `in`).
    [[gnu::always_inline]] int64_t retire_at(ChannelTimes& in, int64_t pushed) { return stage.move(pushed, in, nullptr); }
    int64_t last_retire() const { return stage.last; }  // -1: none yet
    // The LINEAR quad path's lockstep footprint (rtl/unit_recurrence.cpp derives it from
    // retire_at): a pixel pushed into `in` at t - 1, the previous one retired before t, retires
    // at t.
    [[gnu::always_inline]] void step(int64_t t, ChannelTimes& in) {
      in.pop(t);
      stage.last = t;
    }
  } timing;

 private:
  sim::Channel<Response>& filter_;
  sim::Channel<Response>& edge_;
  RequestRing<Rgba8>& pixels_;
  RequestRing<uint64_t>& exit_;
  const RequestRing<uint64_t>& accept_;
  const RequestStream& trace_;
  uint32_t retired_ = 0;
  [[noreturn, gnu::cold, gnu::noinline]] static void beyond_trace(uint32_t id, uint64_t now) {
    throw CheckFailed(fmt::format("response {} beyond the trace at cycle {}", id, now));
  }
};

}  // namespace tfu::rtl
