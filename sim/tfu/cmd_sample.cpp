// tfu sample: run a request trace through the golden sampler (one r,g,b,a line per request), or
// report what the LOD unit / meta MIP-map supplies per request (--query-lod).
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"

namespace tfu::cli {
namespace {

struct SampleOptions {
  TextureOptions tex;
  SamplerOptions smp;
  std::string requests;
  std::string out;
  bool force = false;
  bool query_lod = false;
  bool ideal = false;
};

void run(const SampleOptions& o) {
  OutputFiles outputs(o.force);
  OutputFile* file = o.out == "-" ? nullptr : &outputs.add("--out", o.out);
  const SamplerConfig cfg = sampler_config_from_options(o.smp);
  const Trace tr = load_trace(o.requests);
  const Texture tex = load_texture_from_options(o.tex);
  const Sampler smp(tex, cfg);
  const std::vector<int32_t> lam = trace_lambdas(tr, tex.width(), tex.height());

  std::ostream& os = file ? file->stream() : std::cout;
  if (o.query_lod) {
    os << "# lambda,magnify,level0,level1,blend,level0_width,level0_height,kernel_scale\n";
    for (size_t i = 0; i < tr.requests.size(); ++i) {
      const LodInfo li = smp.lod_info(lam[i]);
      os << fmt::format("{:.8g},{},{},{},{:.8g},{},{},{}\n", li.lambda_q8 / 256.0, li.magnify ? 1 : 0, li.level0,
                        li.level1, li.blend / 256.0, li.level0_width, li.level0_height, li.kernel_scale);
    }
    outputs.commit();
    return;
  }
  for (size_t i = 0; i < tr.requests.size(); ++i) {
    const TraceRequest& r = tr.requests[i];
    if (o.ideal) {
      const auto v = smp.sample_ideal(r.s, r.t, lam[i] / 256.0);
      os << fmt::format("{:.6f},{:.6f},{:.6f},{:.6f}\n", v[0], v[1], v[2], v[3]);
    } else {
      const Rgba8 c = smp.sample(r.s, r.t, lam[i]);
      os << fmt::format("{},{},{},{}\n", c.r, c.g, c.b, c.a);
    }
  }
  outputs.commit();
  if (file) {
    std::cerr << fmt::format("tfu sample: {} requests ({} trace) -> {}\n", tr.requests.size(),
                             trace_mode_name(tr.mode), o.out);
  }
}

}  // namespace

void register_sample(CLI::App& app) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = app.add_subcommand("sample", "Filter a request trace with the golden reference sampler");
  add_texture_options(*cmd, o->tex);
  add_sampler_options(*cmd, o->smp);
  cmd->add_option("--requests", o->requests, "Request trace (docs/traces.md)")->required();
  cmd->add_option("--out", o->out, "Output: one r,g,b,a line per request ('-' = stdout)")->required();
  cmd->add_flag("--force", o->force, "Overwrite --out if it exists");
  cmd->add_flag("--query-lod", o->query_lod,
                "Write the LOD unit's report per request instead: lambda, magnify, levels, blend, level size, kernel scale");
  cmd->add_flag("--ideal", o->ideal, "Write the double-precision ideal result (channels as reals) instead");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
