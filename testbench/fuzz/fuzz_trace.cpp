// Fuzz target (b): a request trace through the reader; a trace that parses is written back and read
// again (every field, descriptor index, screen position and binding line must come back the same,
// floats with the same bits, NaN as NaN), a trace with screen positions is re-ordered, and its
// first 64 requests go through the LOD unit and the golden sampler in three filter families
// (docs/fuzzing.md).
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/raster_order.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

const tfu::Texture& texture() {
  static const tfu::Texture t = [] {
    tfu::Procedural p = tfu::make_procedural("checkerboard", 16);
    tfu::generate_mipmaps(p.texture, tfu::MipMethod::Box);
    return p.texture;
  }();
  return t;
}

bool same_value(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_bindings(const std::vector<tfu::TraceBinding>& a, const std::vector<tfu::TraceBinding>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].index != b[i].index || a[i].spec != b[i].spec || a[i].params != b[i].params) return false;
  return true;
}

bool same_request(const tfu::TraceRequest& a, const tfu::TraceRequest& b) {
  return a.texture == b.texture && a.sampler == b.sampler && a.stage == b.stage && a.x == b.x && a.y == b.y && same_value(a.s, b.s) && same_value(a.t, b.t) && same_value(a.lod, b.lod) && same_value(a.dsdx, b.dsdx) &&
         same_value(a.dtdx, b.dtdx) && same_value(a.dsdy, b.dsdy) && same_value(a.dtdy, b.dtdy);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 65536) return 0;
  std::istringstream in(tfu::fuzz::as_text(data, size));
  tfu::Trace trace;
  try {
    trace = tfu::parse_trace(in, "fuzz.trace");
  } catch (const tfu::InputError&) {
    return 0;
  }
  std::ostringstream out;
  tfu::write_trace(out, trace);
  std::istringstream back_in(out.str());
  const tfu::Trace back = tfu::parse_trace(back_in, "written.trace");  // must not throw
  if (back.mode != trace.mode || back.positions != trace.positions || back.requests.size() != trace.requests.size()) std::abort();
  if (!same_bindings(back.textures, trace.textures) || !same_bindings(back.samplers, trace.samplers)) std::abort();
  for (size_t i = 0; i < trace.requests.size(); ++i)
    if (!same_request(trace.requests[i], back.requests[i])) std::abort();
  if (trace.positions) {  // a trace with positions re-orders into a permutation of its quads
    const tfu::Trace re = tfu::reorder_trace(trace, tfu::raster_order_from_name("morton:8"));
    if (re.requests.size() != trace.requests.size()) std::abort();
  }
  if (trace.requests.size() > 64) trace.requests.resize(64);
  const std::vector<int32_t> lambda = tfu::trace_lambdas(trace, texture().width(), texture().height());
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_NEAREST", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    tfu::SamplerDescriptor cfg;
    cfg.mode = tfu::filter_mode_from_name(mode);
    cfg.wrap_s = tfu::WrapMode::MirroredRepeat;
    cfg.wrap_t = tfu::WrapMode::ClampToBorder;
    const tfu::Sampler smp(texture(), cfg);
    for (size_t i = 0; i < trace.requests.size(); ++i) {
      smp.sample(trace.requests[i].s, trace.requests[i].t, lambda[i]);
      smp.sample_ideal(trace.requests[i].s, trace.requests[i].t, lambda[i] / 256.0);
    }
  }
  return 0;
}
