// request_fifo: the unit's input. Accepts one request per cycle from the trace: a 2x2 quad (quad
// traces) or one pixel (lod / grad traces) with its texture and sampler descriptor indices, and
// stamps each pixel's accept cycle (for the latency histogram). Requests of different textures
// and samplers follow each other in any order.
//
// Ports:
//   out quad  QuadReq (unit_ports.hpp)   valid/ready
#pragma once

#include <algorithm>
#include <vector>

#include "cmodel/trace.hpp"
#include "rtl/request_stream.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class RequestFifo : public sim::Module {
 public:
  // The clocked engine runs on a whole trace (RequestStream::whole): every request is there.
  RequestFifo(sim::Simulator& s, RequestStream& tr, sim::Channel<QuadReq>& o, RequestRing<uint64_t>& accept_cycle)
      : Module(s, "request_fifo"), trace_(tr), out_(o), accept_(accept_cycle) {}
  void evaluate() override {
    if (!out_.can_push() || !trace_.has(next_)) return;
    QuadReq& q = out_.push_slot();  // formed in the output register
    form_quad(trace_, next_, q);
    for (size_t k = 0; k < static_cast<size_t>(q.npix); ++k) accept_[next_ + k] = sim_.cycle();
    next_ += static_cast<size_t>(q.npix);
    sim_.progress();
  }
  // The combinational part: the quad (or pixel) of `trace` that starts at request `first`.
  static void form_quad(const RequestStream& trace, size_t first, QuadReq& q) {
    q.id = static_cast<uint32_t>(first);
    q.npix = trace.mode() == TraceMode::Quad ? 4 : 1;
    for (size_t k = 0; k < static_cast<size_t>(q.npix); ++k) {
      const TraceRequest& r = trace[first + k];
      q.s[k] = r.s;
      q.t[k] = r.t;
    }
    const TraceRequest& r = trace[first];
    q.req = {r.texture, r.sampler, r.stage};
    q.lod = r.lod;
    q.dsdx = r.dsdx;
    q.dtdx = r.dtdx;
    q.dsdy = r.dsdy;
    q.dtdy = r.dtdy;
  }
  std::string state() const override { return out_.state(); }
  // The block's timing for the recurrence engine, beside evaluate(), which pushes a quad in every
  // cycle its output has room (rtl/timing.hpp). Both change together.
  struct Timing {
    int64_t last_push = -1;  // the previous quad's push cycle (-1: none)
    // The cycle the next quad is pushed into `out` (its pixels' accept cycle).
    [[gnu::always_inline]] int64_t push(const ChannelTimes& out) {
      last_push = std::max(last_push + 1, out.room());
      return last_push;
    }
  } timing;

 private:
  RequestStream& trace_;
  sim::Channel<QuadReq>& out_;
  RequestRing<uint64_t>& accept_;
  size_t next_ = 0;
};

}  // namespace tfu::rtl
