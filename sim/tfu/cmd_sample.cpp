// tfu sample: run a request trace through the golden model (one r,g,b,a line per request), or
// report what the LOD unit / meta MIP-map supplies per request (--query-lod). The trace's header
// binds its textures and samplers (docs/traces.md), or the command line describes texture 0 and
// sampler 0.
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cmodel/aniso.hpp"
#include "cmodel/error.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/output_files.hpp"
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
  std::string game_dir;  // OpenArena data of a level trace's oa: textures
  bool force = false;
  bool query_lod = false;
  bool ideal = false;
};

// The double-precision ideal of request i: at the LOD unit's lambda (isotropic samplers, lod
// traces), or the anisotropic ideal from the real-valued derivatives of its quad or gradients.
std::array<double, 4> ideal_sample(const Sampler& smp, const Trace& tr, size_t i, int32_t lambda_q8) {
  const TraceRequest& r = tr.requests[i];
  if (!smp.descriptor().anisotropic() || tr.mode == TraceMode::Lod) return smp.sample_ideal(r.s, r.t, lambda_q8 / 256.0);
  const double w = smp.texture().width(), h = smp.texture().height();
  std::array<double, 4> d{};
  switch (tr.mode) {
    case TraceMode::Lod: break;
    case TraceMode::Grad: d = {r.dsdx * w, r.dtdx * h, r.dsdy * w, r.dtdy * h}; break;
    case TraceMode::Quad: {
      const TraceRequest& q = tr.requests[i - i % 4];
      const TraceRequest &qx = tr.requests[i - i % 4 + 1], &qy = tr.requests[i - i % 4 + 2];
      d = {(double{qx.s} - q.s) * w, (double{qx.t} - q.t) * h, (double{qy.s} - q.s) * w, (double{qy.t} - q.t) * h};
      break;
    }
  }
  return smp.sample_ideal_aniso(r.s, r.t, d);
}

void run(const SampleOptions& o, const CLI::App& cmd) {
  // Every output checked before any work (cmodel/output_files.hpp); written to a temporary, renamed
  // into place by commit() only when complete.
  OutputFiles outputs(o.force);
  OutputFile* file = o.out == "-" ? nullptr : &outputs.add("--out", o.out);
  Trace tr = load_trace(o.requests);
  const std::optional<TextureSpec> spec = texture_spec_given(cmd, o.tex);
  int line_bytes = 64;  // tiles of --tile-bytes, if given (the static edge shapes follow them)
  if (spec && spec->params.contains("tile_bytes")) {
    const std::string& text = spec->params.at("tile_bytes");  // strtol, not atoi: no overflow on any text
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || text.empty() || !valid_tile_bytes(static_cast<int>(std::clamp(v, 0L, 4096L))))
      throw InputError(fmt::format("--tile-bytes '{}' must be 64, 256 or 1024", quote_input(text)));
    line_bytes = static_cast<int>(v);
  }
  const Frame frame = frame_for_trace(cmd, o.tex, o.smp, tr, line_bytes, o.game_dir);
  const GoldenUnit golden(frame);

  std::ostream& os = file ? file->stream() : std::cout;
  if (o.query_lod) os << "# lambda,magnify,level0,level1,blend,level0_width,level0_height,kernel_scale,px,py,probes\n";
  AnisoLod lod;
  for (size_t i = 0; i < tr.requests.size(); ++i) {
    const TraceRequest& r = tr.requests[i];
    const Sampler& smp = golden.sampler(r.texture, r.sampler);
    if (tr.mode != TraceMode::Quad || i % 4 == 0) {
      // The report forms Px and Py for every sampler (request_lod; with max_aniso 1 its lambda is the
      // isotropic unit's bit for bit, N = 1), the samples take the golden unit's LOD.
      const TextureDescriptor& d = frame.regs.textures.at(r.texture);
      lod = o.query_lod ? request_lod(tr, i, d.width, d.height, smp.descriptor().aniso()) : golden.lod(tr, i);
    }
    if (o.query_lod) {
      const LodInfo li = smp.lod_info(lod.lambda_q8);
      // Px and Py: the axis lengths of the footprint in level-0 texels (floor(sqrt) in Q.16; 0 in
      // lod traces, which have no derivatives), N the probes per pixel.
      os << fmt::format("{:.8g},{},{},{},{:.8g},{},{},{},{:.8g},{:.8g},{}\n", li.lambda_clamped_q8 / 256.0,
                        li.magnify ? 1 : 0, li.level0, li.level1, li.blend / 256.0, li.level0_width, li.level0_height,
                        li.kernel_scale, axis_length_q16(lod.px2_q32) / 65536.0, axis_length_q16(lod.py2_q32) / 65536.0,
                        lod.probes);
    } else if (o.ideal) {
      const auto v = ideal_sample(smp, tr, i, lod.lambda_q8);
      os << fmt::format("{:.6f},{:.6f},{:.6f},{:.6f}\n", v[0], v[1], v[2], v[3]);
    } else {
      const Rgba8 c = smp.sample(r.s, r.t, lod);
      os << fmt::format("{},{},{},{}\n", c.r, c.g, c.b, c.a);
    }
  }
  outputs.commit();
  if (file) {
    print_summary_line(fmt::format("tfu sample: {} requests ({} trace) -> {}", tr.requests.size(), trace_mode_name(tr.mode), o.out));
  }
}

}  // namespace

void register_sample(CLI::App& app) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = app.add_subcommand("sample", "Filter a request trace with the golden reference sampler");
  add_plain_option(*cmd);
  add_texture_options(*cmd, o->tex, false);
  add_sampler_options(*cmd, o->smp);
  cmd->add_option("--requests", o->requests, "Request trace (docs/traces.md)")->required();
  cmd->add_option("--out", o->out, "Output: one r,g,b,a line per request ('-' = stdout)")->required();
  cmd->add_option("--game-dir", o->game_dir, "OpenArena data directory for a level trace's oa: textures (default: $TFU_OPENARENA_DIR or Debian's)");
  cmd->add_flag("--force", o->force, "Overwrite --out if it exists");
  cmd->add_flag("--query-lod", o->query_lod,
                "Write the LOD unit's report per request instead: lambda, magnify, levels, blend, level size, kernel scale, "
                "Px, Py (texels), probes N");
  cmd->add_flag("--ideal", o->ideal, "Write the double-precision ideal result (channels as reals) instead");
  cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace tfu::cli
