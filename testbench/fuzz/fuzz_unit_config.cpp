// Fuzz target (c): a unit configuration JSON through its reader and, when it is valid, a short
// simulation (16 pixels of a 16x16 texture, the filter mode chosen by the input's length) whose
// every output must equal the golden model's (docs/fuzzing.md).
#include <cstdio>
#include <cstdlib>

#include "cmodel/error.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

const tfu::Texture& texture() {
  static const tfu::Texture t = [] {
    tfu::Procedural p = tfu::make_procedural("text", 16);
    tfu::generate_mipmaps(p.texture, tfu::MipMethod::Box);
    return p.texture;
  }();
  return t;
}

// Four quads: magnified, minified, across the wrap seam, and at an oblique angle.
const tfu::Trace& trace() {
  static const tfu::Trace t = [] {
    tfu::Trace tr;
    tr.mode = tfu::TraceMode::Quad;
    const float quads[4][4][2] = {{{0.10f, 0.10f}, {0.11f, 0.10f}, {0.10f, 0.11f}, {0.11f, 0.11f}},
                                  {{0.20f, 0.30f}, {0.45f, 0.30f}, {0.20f, 0.55f}, {0.45f, 0.55f}},
                                  {{0.97f, 0.98f}, {1.03f, 0.98f}, {0.97f, 1.04f}, {1.03f, 1.04f}},
                                  {{0.50f, 0.50f}, {0.56f, 0.52f}, {0.47f, 0.61f}, {0.53f, 0.63f}}};
    for (const auto& q : quads)
      for (const auto& p : q) {
        tfu::TraceRequest r;
        r.s = p[0];
        r.t = p[1];
        tr.requests.push_back(r);
      }
    return tr;
  }();
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return 0;
  tfu::rtl::UnitConfig u;
  try {
    u = tfu::rtl::unit_config_from_json(tfu::fuzz::as_text(data, size), "fuzz.json");
  } catch (const tfu::InputError&) {
    return 0;
  }
  tfu::SamplerConfig cfg;
  cfg.mode = tfu::all_filter_modes()[size % tfu::all_filter_modes().size()];
  const tfu::rtl::UnitOutput got = tfu::rtl::run_unit(texture(), cfg, trace(), u);  // a valid config: no error
  const tfu::Sampler golden(texture(), tfu::rtl::golden_sampler_config(cfg, u));
  const std::vector<int32_t> lambda = tfu::trace_lambdas(trace(), texture().width(), texture().height());
  for (size_t i = 0; i < trace().requests.size(); ++i) {
    const tfu::Rgba8 want = tfu::rtl::golden_pixel(golden, u, got, trace().requests[i], lambda[i], i);
    if (want != got.pixels[i]) {
      std::fprintf(stderr, "mismatch: %s request %zu\n", tfu::filter_mode_name(cfg.mode).c_str(), i);
      std::abort();
    }
  }
  return 0;
}
