#include "sim/tfu/sampler_options.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {

std::string flag_of(const std::string& key) {
  std::string f = "--" + key;
  std::replace(f.begin(), f.end(), '_', '-');
  return f;
}

void add_texture_options(CLI::App& cmd, TextureOptions& o, bool texture_required) {
  CLI::Option* t = cmd.add_option("--texture", o.texture,
                                  "Texture image file (PNG, JPEG, TIFF, OpenEXR, ...) or proc:NAME[:SIZE] (checkerboard, "
                                  "text, zoneplate, lightmap, noise)");
  if (texture_required) t->required();
  static const std::map<std::string, std::string> help = {
      {"format",
       "Texel format: auto (from the file), rgba8, l8, vs16x2 (bytes as two signed 16-bit channels), srgba8 (sRGB "
       "colour, docs/srgb.md)"},
      {"mipmaps", "MIP levels: auto (the file's stored levels, else box), stored, none, box, gaussian, edge"},
      {"alpha", "Edge-preserving MIP weight alpha of Lee & Jen Eq. 7 (0..1)"},
      {"layout", "Memory layout: tiled (one tile per cache line) or linear rows"},
      {"tile_bytes", "Tiled layout: bytes per tile, one cache line (64, 256 or 1024)"},
      {"compress", "Compress the texture at load as a driver does: none (default), a block format (bc1, bc3, bc7, etc2, "
                   "astc4x4 ... astc12x12) or s3tc (ioquake3's rule: bc1a when every alpha is 255, else uncompressed; "
                   "docs/compressed.md); a DDS, KTX or .astc file is read compressed as it is. tfu sim: also an oa: level "
                   "scene's base textures"},
      {"srgb",
       "true: the colour channels are sRGB codes, decoded to linear before filtering and the result re-encoded "
       "(format srgba8, docs/srgb.md); false (default): filtered as stored"}};
  for (const char* key : texture_param_keys()) cmd.add_option(flag_of(key), o.values[key], help.at(key));
}

void add_plain_option(CLI::App& cmd) {
  cmd.add_flag_callback(
      "--plain",
      [] {
        set_fast_paths(false);
        ::setenv("TFU_PLAIN", "1", 1);
      },
      "Run the plain datapaths instead of the speed-only fast paths (the same results; also TFU_PLAIN=1)");
}

void add_sampler_options(CLI::App& cmd, SamplerOptions& o) {
  for (const SamplerParam& p : sampler_params()) cmd.add_option(flag_of(p.key), o.values[p.key], p.meaning);
  cmd.add_option("--wrap", o.wrap, "Wrap mode for s and t (--wrap-s / --wrap-t override it)");
}

std::optional<TextureSpec> texture_spec_given(const CLI::App& cmd, const TextureOptions& o) {
  TextureSpec spec;
  spec.source = o.texture;
  for (const char* key : texture_param_keys())
    if (cmd.count(flag_of(key)) > 0) spec.params[key] = o.values.at(key);
  if (o.texture.empty()) {
    if (!spec.params.empty()) throw InputError(fmt::format("{} needs --texture", flag_of(spec.params.begin()->first)));
    return std::nullopt;
  }
  return spec;
}

Params sampler_params_given(const CLI::App& cmd, const SamplerOptions& o) {
  Params p;
  if (cmd.count("--wrap") > 0) p["wrap_s"] = p["wrap_t"] = o.wrap;
  for (const SamplerParam& q : sampler_params())
    if (cmd.count(flag_of(q.key)) > 0) p[q.key] = o.values.at(q.key);
  // Each value checked on its own, so that an error names the flag.
  for (const auto& [key, value] : p) {
    SamplerDescriptor scratch;
    try {
      set_sampler_param(scratch, key, value);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", cmd.count("--wrap") > 0 && key.rfind("wrap_", 0) == 0 && cmd.count(flag_of(key)) == 0
                                                 ? std::string("--wrap")
                                                 : flag_of(key),
                                   e.what()));
    }
  }
  return p;
}

Frame frame_for_trace(const CLI::App& cmd, const TextureOptions& t, const SamplerOptions& s, Trace& trace, int line_bytes,
                      const std::string& game_dir) {
  FrameDefaults d;
  d.game_dir = game_dir;
  d.texture = texture_spec_given(cmd, t);
  if (d.texture && !trace.textures.empty())
    throw InputError(fmt::format("--texture: {} binds its own textures (give it no --texture)", trace.textures.front().where));
  if (!d.texture && trace.textures.empty()) throw InputError(fmt::format("{} binds no texture: give --texture", trace.source));
  const Params given = sampler_params_given(cmd, s);
  if (trace.samplers.empty()) {
    d.sampler = given;
  } else {
    d.sampler_overrides = given;
  }
  return frame_from_trace(trace, d, line_bytes);
}

void add_gl_trace_options(CLI::App& cmd, GlTraceOptions& o, const char* through) {
  cmd.add_option("--gl-trace", o.trace,
                 fmt::format("An apitrace trace of a game's OpenGL 1.x command stream: replay --frame through {} (docs/gl-replay.md)",
                             through));
  cmd.add_option("--frame", o.frame, "With --gl-trace: the frame replayed (0: the calls up to the first glXSwapBuffers)")
      ->capture_default_str();
  cmd.add_option("--alpha-bits", o.alpha_bits,
                 "With --gl-trace: the framebuffer's alpha bits, 0 or 8 (default -1: as the trace's visual asks; glretrace draws "
                 "into a visual of its own)")
      ->capture_default_str();
  cmd.add_option(
      "--gl-min-filter", o.min_filter,
      "With --gl-trace: the minification filter of every mipmapped texture, as the engine's r_textureMode sets it "
      "(GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR_MIPMAP_LINEAR, GL_NEAREST_MIPMAP_*; its base filter also magnifies); "
      "default: as traced");
  cmd.add_option("--gl-max-aniso", o.max_aniso,
                 "With --gl-trace: the maximum anisotropy (1..16) of every mipmapped texture, as the engine's "
                 "r_ext_max_anisotropy "
                 "sets it; default 0: as traced");
  cmd.add_option(
      "--draws-out", o.draws_out,
      "With --gl-trace: write one CSV row per draw of the frame (GL textures, fragment state, depth range, projection, "
      "modelview, locked-arrays pass, triangles, quads, pixels, requests; docs/gl-replay.md)");
}

gl::ReplayOptions gl_replay_options(const GlTraceOptions& o, int line_bytes) {
  gl::ReplayOptions ro;
  ro.line_bytes = line_bytes;
  ro.alpha_bits = o.alpha_bits;
  ro.min_filter = o.min_filter;
  ro.max_aniso = o.max_aniso;
  return ro;
}

const std::vector<const char*>& gl_trace_only_options() {
  static const std::vector<const char*> v{"--frame", "--alpha-bits", "--gl-min-filter", "--gl-max-aniso",
                                          "--draws-out"};
  return v;
}

}  // namespace tfu::cli
