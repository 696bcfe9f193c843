// tfu aniso-compare: anisotropic filtering against an outside implementation (OpenImageIO). A
// scene (built-in, JSON or an OpenArena level oa:MAP[:SPAWN]) is rendered to get its quads; every covered pixel becomes a grad-mode request
// (s, t of the pixel, the quad's coarse derivatives ds/dx = s(1,0) - s(0,0), ... as gradients), and
// the same requests are filtered by
//   ours   the golden model (GoldenUnit: the LOD unit on the gradients, Sampler), trilinear and with
//          maxAniso N on the base stages (LINEAR_MIPMAP_LINEAR probes)
//   OIIO   OpenImageIO's TextureSystem::texture() with the same derivatives, MipModeTrilinear and
//          MipModeAniso with TextureOpt::anisotropic = N, bilinear interpolation, the same wraps,
//          reading the same texels: every texture's MIP chain (ours, level by level) written to a
//          tiled MIP-mapped TIFF (automip off)
// and each result image is measured against the scene's supersampled ground truth (PSNR, SSIM).
// Writes a montage (truth, ours trilinear, ours anisotropic, OIIO anisotropic, OIIO trilinear) and
// prints a Markdown table row per result (docs/anisotropic.md). Other stages (a light map) are
// looked up isotropically by both, with their own samplers.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/montage.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/temp_paths.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct AnisoCompareOptions {
  std::string scene = "grazing";
  int max_aniso = 16;
  int width = 0, height = 0;  // 0: the scene's size
  std::string game_dir;       // OpenArena data for oa: scenes
  std::string montage, json;
  bool force = false;
};

// The render's quad requests as grad-mode requests: each pixel keeps its (s, t) and takes its
// quad's coarse derivatives as gradients.
Trace grad_trace(const Trace& quads) {
  Trace g;
  g.mode = TraceMode::Grad;
  g.requests = quads.requests;
  for (size_t q = 0; q + 3 < quads.requests.size(); q += 4) {
    const TraceRequest &p0 = quads.requests[q], &px = quads.requests[q + 1], &py = quads.requests[q + 2];
    for (size_t k = 0; k < 4; ++k) {
      TraceRequest& r = g.requests[q + k];
      r.dsdx = px.s - p0.s;
      r.dtdx = px.t - p0.t;
      r.dsdy = py.s - p0.s;
      r.dtdy = py.t - p0.t;
    }
  }
  return g;
}

// A texture's levels (ours) as a tiled, MIP-mapped 8-bit RGBA TIFF for the TextureSystem (one TIFF
// directory per level, as OIIO's maketx writes them), checked by reading the level sizes back.
void write_mip_tiff(const Texture& tex, const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw CheckFailed(fmt::format("OpenImageIO cannot write '{}'", path));
  for (size_t l = 0; l < tex.levels.size(); ++l) {
    const Image& img = tex.levels[l];
    OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
    spec.tile_width = spec.tile_height = 64;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("textureformat", "Plain Texture");
    if (!out->open(path, spec, l == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendSubimage) ||
        !out->write_image(OIIO::TypeDesc::UINT8, img.texels.data()))
      throw CheckFailed(fmt::format("writing '{}': {}", path, out->geterror()));
  }
  out->close();
  auto in = OIIO::ImageInput::open(path);
  for (size_t l = 0; l < tex.levels.size(); ++l)
    if (!in || !in->seek_subimage(0, static_cast<int>(l)) || in->spec().width != tex.levels[l].width ||
        in->spec().height != tex.levels[l].height)
      throw CheckFailed(fmt::format("OpenImageIO does not read '{}' back as {} MIP levels", path, tex.levels.size()));
}

OIIO::TextureOpt::Wrap oiio_wrap(WrapMode w) {
  switch (w) {
    case WrapMode::Repeat: return OIIO::TextureOpt::WrapPeriodic;
    case WrapMode::MirroredRepeat: return OIIO::TextureOpt::WrapMirror;
    case WrapMode::ClampToEdge: return OIIO::TextureOpt::WrapClamp;
    case WrapMode::ClampToBorder: return OIIO::TextureOpt::WrapBlack;
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

// TextureOpt for one of our samplers: NEAREST / LINEAR / CUBIC (B-spline in OIIO) interpolation
// (EDGE_PRESERVING has no counterpart: bilinear), the MIP mode, anisotropic when the sampler is.
OIIO::TextureOpt oiio_opt(const SamplerDescriptor& s) {
  OIIO::TextureOpt o;
  o.interpmode = s.mode.base == BaseFilter::Nearest ? OIIO::TextureOpt::InterpClosest
                 : s.mode.base == BaseFilter::Cubic ? OIIO::TextureOpt::InterpBicubic
                                                    : OIIO::TextureOpt::InterpBilinear;
  o.mipmode = s.mode.mip == MipMode::None      ? OIIO::TextureOpt::MipModeNoMIP
              : s.mode.mip == MipMode::Nearest ? OIIO::TextureOpt::MipModeOneLevel
              : s.anisotropic()                ? OIIO::TextureOpt::MipModeAniso
                                               : OIIO::TextureOpt::MipModeTrilinear;
  o.anisotropic = s.anisotropic() ? s.max_aniso : 1;
  o.swrap = oiio_wrap(s.wrap_s);
  o.twrap = oiio_wrap(s.wrap_t);
  return o;
}

struct Lookup {
  std::string label;
  Image image;
  double psnr = 0, ssim = 0;
};

// One render of the scene (quads, truth, frame) with the base stages' max_aniso.
RenderResult render_quads(const Scene& scene, int max_aniso, bool truth) {
  RenderOptions ro;
  ro.filter = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
  ro.sampler_overrides["max_aniso"] = std::to_string(max_aniso);
  ro.trace = true;
  ro.ground_truth = truth;
  return render_scene(scene, ro);
}

Image ours(const Scene& scene, const RenderResult& r) {
  const Trace g = grad_trace(r.trace);
  const GoldenUnit golden(r.frame->frame);
  std::vector<Rgba8> out(g.requests.size());
  for (size_t i = 0; i < g.requests.size(); ++i) out[i] = golden.sample(g.requests[i], golden.lod(g, i));
  Image img = r.image;
  compose_quad_outputs(scene, r.quad_targets, out, img);
  return img;
}

Image oiio(const Scene& scene, const RenderResult& r, const std::filesystem::path& dir) {
  const Frame& frame = r.frame->frame;
  // One TextureSystem for the process, never destroyed: OpenImageIO 2.4's TextureSystem::destroy
  // deletes its implementation object through the base type (AddressSanitizer reports a
  // new-delete-type-mismatch inside libOpenImageIO). It stays reachable, so it is no leak; its
  // cached files are dropped after each use (invalidate_all below).
  static OIIO::TextureSystem* const ts = OIIO::TextureSystem::create(false);
  ts->attribute("automip", 0);
  std::vector<OIIO::TextureSystem::TextureHandle*> handles;
  for (size_t t = 0; t < frame.textures.size(); ++t) {
    // OIIO reads the decoded levels; only for RGBA8 are they the texels our sampler reads.
    if (frame.textures[t].texels->format != TexelFormat::RGBA8)
      throw InputError(fmt::format("aniso-compare: the scene's texture {} is {}; the comparison takes RGBA8 textures only", t,
                                   texel_format_name(frame.textures[t].texels->format)));
    const std::string path = (dir / fmt::format("texture{}.tif", t)).string();
    write_mip_tiff(*frame.textures[t].texels, path);
    handles.push_back(ts->get_texture_handle(OIIO::ustring(path)));
  }
  OIIO::TextureSystem::Perthread* pt = ts->get_perthread_info();
  const Trace g = grad_trace(r.trace);
  std::vector<Rgba8> out(g.requests.size());
  for (size_t i = 0; i < g.requests.size(); ++i) {
    const TraceRequest& q = g.requests[i];
    OIIO::TextureOpt opt = oiio_opt(frame.regs.samplers[q.sampler]);
    float res[4] = {0, 0, 0, 1};
    if (!ts->texture(handles[q.texture], pt, opt, q.s, q.t, q.dsdx, q.dtdx, q.dsdy, q.dtdy, 4, res))
      throw CheckFailed(fmt::format("OpenImageIO texture(): {}", ts->geterror()));
    const auto code = [](float x) { return static_cast<uint8_t>(std::clamp(std::lround(255.0f * x), 0L, 255L)); };
    out[i] = {code(res[0]), code(res[1]), code(res[2]), code(res[3])};
  }
  ts->invalidate_all(true);
  Image img = r.image;
  compose_quad_outputs(scene, r.quad_targets, out, img);
  return img;
}

void run(const AnisoCompareOptions& o) {
  if (o.max_aniso < 2 || o.max_aniso > kMaxAniso) throw InputError(fmt::format("--max-aniso must be in 2..16, got {}", o.max_aniso));
  if (o.width < 0 || o.height < 0 || o.width == 1 || o.height == 1 || o.width > kMaxRenderSize || o.height > kMaxRenderSize)
    throw InputError(fmt::format("--width/--height must be in 2..{} (0: the scene's own size)", kMaxRenderSize));
  // Both outputs reserved before the run (cmodel/output_files.hpp): distinct files, none replaced
  // without --force, written to temporaries and renamed only when the run completes.
  OutputFiles outputs(o.force);
  OutputFile* montage_file = o.montage.empty() ? nullptr : &outputs.add_image("--montage", o.montage);
  OutputFile* json_file = o.json.empty() ? nullptr : &outputs.add("--json", o.json);
  const Scene scene = open_scene({o.scene, o.width, o.height, o.game_dir});
  const RenderResult iso = render_quads(scene, 1, true), aniso = render_quads(scene, o.max_aniso, false);
  std::vector<Lookup> looks;
  {
    // OIIO reads the textures from files: a private directory of this run (mkdtemp), removed after.
    const TempDir dir("tfu-aniso-compare");
    looks = {{"ours trilinear", ours(scene, iso)},
             {fmt::format("ours aniso {}", o.max_aniso), ours(scene, aniso)},
             {fmt::format("OIIO aniso {}", o.max_aniso), oiio(scene, aniso, dir.path())},
             {"OIIO trilinear", oiio(scene, iso, dir.path())}};
  }
  nlohmann::json js;
  std::cout << fmt::format("tfu aniso-compare: scene {} at {}x{}, {} grad-mode requests\n", o.scene, scene.width, scene.height,
                           iso.trace.requests.size());
  // Cross-check: each of ours against OIIO's lookup of the same kind (trilinear <-> trilinear,
  // aniso <-> aniso), mean and max absolute difference in 8-bit levels over RGB.
  const size_t counterpart[4] = {3, 2, 1, 0};
  std::cout << "| scene | lookups | PSNR vs truth (dB) | SSIM vs truth | mean / max abs diff vs the other side's same mode |\n"
               "|---|---|---:|---:|---:|\n";
  for (size_t k = 0; k < looks.size(); ++k) {
    Lookup& l = looks[k];
    l.psnr = psnr_db(l.image, iso.truth);
    l.ssim = ssim_luma(l.image, iso.truth);
    const DiffStats d = diff_stats(l.image, looks[counterpart[k]].image);
    std::cout << fmt::format("| {} | {} | {} | {:.4f} | {:.2f} / {} |\n", o.scene, l.label, format_metric(l.psnr, 2), l.ssim,
                             d.mean_abs, d.max_abs);
    js[l.label] = {{"psnr_db", l.psnr}, {"ssim", l.ssim}, {"mean_abs_diff_other_side", d.mean_abs}, {"max_abs_diff_other_side", d.max_abs}};
  }
  if (montage_file) {
    std::vector<Image> tiles{iso.truth};
    std::vector<std::string> labels{"ground truth"};
    for (const Lookup& l : {looks[0], looks[1], looks[2], looks[3]}) {
      tiles.push_back(l.image);
      labels.push_back(l.label);
    }
    montage_file->write_image(montage(tiles, labels, static_cast<int>(tiles.size())));
  }
  if (json_file) json_file->stream() << json_dump(js, 2) << '\n';
  outputs.commit();
  if (montage_file) std::cout << "  montage -> " << o.montage << '\n';
}

}  // namespace

void register_aniso_compare(CLI::App& app) {
  auto o = std::make_shared<AnisoCompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "aniso-compare", "Anisotropic filtering, ours vs OpenImageIO's TextureSystem, on a scene's grad-mode requests: PSNR/SSIM vs truth");
  cmd->add_option("--scene", o->scene, "Built-in scene, scene JSON or oa:MAP[:SPAWN]")->capture_default_str();
  cmd->add_option("--game-dir", o->game_dir, "OpenArena data directory for oa: scenes (default: $TFU_OPENARENA_DIR or Debian's)");
  cmd->add_option("--max-aniso", o->max_aniso, "Probes per pixel at most (ours: maxAniso; OIIO: TextureOpt::anisotropic), 2..16")
      ->capture_default_str();
  cmd->add_option("--width", o->width, "Render width (0: the scene's)");
  cmd->add_option("--height", o->height, "Render height (0: the scene's)");
  cmd->add_option("--montage", o->montage, "Write a labelled montage PNG (truth, ours, OIIO)");
  cmd->add_option("--json", o->json, "Write the metrics as JSON");
  cmd->add_flag("--force", o->force, "Overwrite output files that exist");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
