// tfu_sv_bench: speed of the Verilated edge-preserving top (rtl/sv/edge/tfu_edge_interp_top.sv,
// one result per clock) against the C++ datapath (lee_jen::edge_preserving_interpolate) on the same
// inputs: the EDGE_PRESERVING footprints of the scene "text_quad" (cross kernel and 4x4 cache-block
// T/L kernels), repeated. Not a test; it also counts mismatches as a sanity check.
//
//   tfu_sv_bench [SAMPLES]     (default 2000000)
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#include <fmt/format.h>

#include "cmodel/edge_filter.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"
#include "rtl/tfu_unit.hpp"

#include "Vtfu_edge_interp_top.h"
#include "verilated.h"

namespace {

namespace lj = tfu::lee_jen;

uint32_t pack(const tfu::Texel4& c) {
  return static_cast<uint32_t>(c[0]) | static_cast<uint32_t>(c[1]) << 8 | static_cast<uint32_t>(c[2]) << 16 |
         static_cast<uint32_t>(c[3]) << 24;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const long samples = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 2'000'000;
    if (samples <= 0) {
      std::fprintf(stderr, "usage: tfu_sv_bench [SAMPLES]\n");
      return 2;
    }
    tfu::Scene scene = tfu::load_scene("text_quad");
    scene.width = 128;
    scene.height = 96;
    tfu::RenderOptions o;
    o.trace = true;
    o.threads = 1;
    const tfu::Trace trace = tfu::render_scene(scene, o).trace;
    const tfu::Mesh& mesh = scene.meshes.front();
    std::vector<tfu::EdgeFootprint> fps;
    for (const bool blocks : {false, true}) {
      tfu::SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.mode = {tfu::BaseFilter::EdgePreserving, tfu::MipMode::None};
      cfg.edge_shape = blocks ? tfu::EdgeShape::Static : tfu::EdgeShape::Cross;
      const tfu::Sampler smp(*mesh.stages[0].texture, cfg);
      for (const tfu::TraceRequest& q : trace.requests) fps.push_back(smp.edge_footprint(0, q.s, q.t));
    }
    const auto n = static_cast<size_t>(samples);

    // C++ datapath.
    std::vector<uint32_t> cpp(n);
    auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < n; ++i) {
      const tfu::EdgeFootprint& f = fps[i % fps.size()];
      cpp[i] = pack(lj::edge_preserving_interpolate(f.texels, f.mask, f.fu, f.fv, tfu::TexelFormat::RGBA8));
    }
    const double t_cpp = seconds_since(t0);

    // Verilated top: one request per clock, results kLatency = 3 clocks later.
    VerilatedContext ctx;
    Vtfu_edge_interp_top m{&ctx};
    m.clk = 0;
    m.rst_n = 0;
    m.in_valid = 0;
    m.eval();
    for (int i = 0; i < 3; ++i) {
      m.clk = 1;
      m.eval();
      m.clk = 0;
      m.eval();
    }
    m.rst_n = 1;
    size_t got = 0, mismatches = 0;
    t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < n + 2; ++i) {
      m.in_valid = i < n;
      if (i < n) {
        const tfu::EdgeFootprint& f = fps[i % fps.size()];
        for (size_t k = 0; k < f.texels.size(); ++k) m.texels[k] = pack(f.texels[k]);
        m.shape = f.mask;
        m.fu = static_cast<uint8_t>(f.fu);
        m.fv = static_cast<uint8_t>(f.fv);
      }
      m.clk = 1;
      m.eval();
      m.clk = 0;
      m.eval();
      if (m.out_valid) mismatches += m.c != cpp[got++];
    }
    const double t_sv = seconds_since(t0);

    fmt::print("edge-preserving datapath, {} samples (text_quad 128x96 footprints, cross + 4x4 T/L)\n", n);
    fmt::print("  C++ lee_jen::edge_preserving_interpolate   {:10.3f} M samples/s\n", static_cast<double>(n) / t_cpp * 1e-6);
    fmt::print("  Verilated tfu_edge_interp_top (1/clock)    {:10.3f} M samples/s\n", static_cast<double>(n) / t_sv * 1e-6);
    fmt::print("  ratio C++ / Verilator                      {:10.2f}\n", t_sv / t_cpp);
    {
      // The whole C++ cycle model (rtl/, static 4x4 shapes) on the same scene trace, for scale: it
      // adds the LOD unit, address generation, kernel selection, the cache and the pipeline.
      tfu::SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.mode = {tfu::BaseFilter::EdgePreserving, tfu::MipMode::None};
      cfg.edge_shape = tfu::EdgeShape::Static;
      tfu::FrameBuilder fb(64);
      fb.add_texture(mesh.stages[0].texture, mesh.stages[0].spec);
      fb.add_sampler(cfg);
      const tfu::Frame frame = fb.finish();
      tfu::Trace big;
      big.mode = trace.mode;
      while (big.requests.size() < n)
        big.requests.insert(big.requests.end(), trace.requests.begin(), trace.requests.end());
      const auto t1 = std::chrono::steady_clock::now();
      for (tfu::TraceRequest& q : big.requests) q.texture = q.sampler = 0;
      const tfu::rtl::UnitOutput u = tfu::rtl::run_unit(frame, big, tfu::rtl::UnitConfig{});
      const double t_unit = seconds_since(t1);
      fmt::print("  C++ cycle model rtl::run_unit (whole unit) {:10.3f} M samples/s ({} pixels, {} cycles)\n",
                 static_cast<double>(big.requests.size()) / t_unit * 1e-6, u.pixels.size(), u.cycles);
    }
    fmt::print("  results {} of {}, mismatches {}\n", got, n, mismatches);
    return (got == n && mismatches == 0) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tfu_sv_bench: error: %s\n", e.what());
    return 1;
  }
}
