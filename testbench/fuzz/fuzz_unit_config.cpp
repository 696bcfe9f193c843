// Fuzz target (c): a unit configuration JSON through its reader and, when it is valid, a short
// simulation (16 pixels of a 16x16 texture, the filter mode chosen by the input's length) whose
// every output must equal the golden model's (docs/fuzzing.md). Harness limit: caches above 1 MiB
// are read but not simulated (1 GiB of tags per input would be slow, not wrong).
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

std::shared_ptr<const tfu::Texture> texture() {
  static const auto t = [] {
    tfu::Procedural p = tfu::make_procedural("text", 16);
    tfu::generate_mipmaps(p.texture, tfu::MipMethod::Box);
    return std::make_shared<const tfu::Texture>(p.texture);
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
  // The harness's cost limit: the largest valid cache (1 GiB of tags) is the unit test's job.
  if (u.cache.capacity_bytes > (1 << 20)) return 0;
  tfu::SamplerDescriptor smp;
  smp.mode = tfu::all_filter_modes()[size % tfu::all_filter_modes().size()];
  tfu::FrameBuilder fb(u.cache.line_bytes);
  const int tex = fb.add_texture(texture(), {"proc:text:16", {}});
  const int sampler = fb.add_sampler(smp);
  tfu::Trace tr = trace();
  for (tfu::TraceRequest& r : tr.requests) {
    r.texture = static_cast<uint16_t>(fb.bind(tex, sampler));
    r.sampler = static_cast<uint8_t>(sampler);
  }
  const tfu::Frame frame = fb.finish();
  const tfu::rtl::UnitOutput got = tfu::rtl::run_unit(frame, tr, u);  // a valid config: no error
  const tfu::GoldenUnit golden(frame);
  const std::string mismatch = tfu::rtl::first_mismatch(tr, tfu::rtl::golden_outputs(golden, tr, got), got);
  if (!mismatch.empty()) {
    std::fprintf(stderr, "mismatch: %s: %s\n", tfu::filter_mode_name(smp.mode).c_str(), mismatch.c_str());
    std::abort();
  }
  return 0;
}
