#include "sim/tfu/sampler_options.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "sim/tfu/choices.hpp"

namespace tfu::cli {

void add_texture_options(CLI::App& cmd, TextureOptions& o) {
  cmd.add_option("--texture", o.texture, "Texture image file (PNG, JPEG, TIFF, OpenEXR, ...) or proc:NAME[:SIZE] (checkerboard, text, zoneplate, lightmap, noise)")->required();
  cmd.add_option("--format", o.format, "Texel format: auto (from the file), rgba8, l8, vs16x2 (bytes as two signed 16-bit channels)");
  cmd.add_option("--mipmaps", o.mipmaps,
                 "MIP levels: auto (the file's stored levels, else box), stored, none, box, gaussian, edge");
  cmd.add_option("--alpha", o.alpha, "Edge-preserving MIP weight alpha of Lee & Jen Eq. 7 (0..1)");
}

void add_sampler_options(CLI::App& cmd, SamplerOptions& o) {
  cmd.add_option("--filter", o.filter, "Filter mode, e.g. LINEAR_MIPMAP_LINEAR, cubic, edge-preserving");
  cmd.add_option("--kernel", o.kernel, "CUBIC kernel: bspline, catmull-rom, mitchell, kaiser, blackman, bspline-interp, ...");
  cmd.add_option("--wrap", o.wrap, "Wrap mode for s and t: repeat, mirrored-repeat, clamp-to-edge, clamp-to-border");
  cmd.add_option("--wrap-s", o.wrap_s, "Wrap mode for s (overrides --wrap)");
  cmd.add_option("--wrap-t", o.wrap_t, "Wrap mode for t (overrides --wrap)");
  cmd.add_option("--border", o.border, "Border texel word r,g,b,a (0..255 each) for clamp-to-border");
  cmd.add_option("--lod-bias", o.lod_bias, "LOD bias added to lambda");
  cmd.add_option("--min-lod", o.min_lod, "Lower clamp of lambda");
  cmd.add_option("--max-lod", o.max_lod, "Upper clamp of lambda");
  cmd.add_option("--rom-samples", o.rom_samples, "CUBIC weight ROM: samples per tile (16..512)");
  cmd.add_option("--rom-bits", o.rom_bits, "CUBIC weight ROM: magnitude bits (4..16)");
  cmd.add_option("--rom-recon", o.rom_recon, "CUBIC weight reconstruction: nearest or linear");
  cmd.add_option("--edge-shape", o.edge_shape, "Edge-preserving kernel shape: cross, or cache-block (T/L at block borders)");
  cmd.add_option("--cache-block", o.cache_block, "Cache block size B (texels) for --edge-shape cache-block");
}

namespace {

Rgba8 parse_border(const std::string& s) {
  std::istringstream in(s);
  std::string field;
  int v[4];
  int n = 0;
  while (std::getline(in, field, ',')) {
    std::size_t used = 0;
    int x = -1;
    try {
      x = std::stoi(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (n >= 4 || used != field.size() || x < 0 || x > 255)
      throw InputError(fmt::format("--border '{}' is not four integers 0..255 separated by commas", quote_input(s)));
    v[n++] = x;
  }
  if (n != 4) throw InputError(fmt::format("--border '{}' is not four integers 0..255 separated by commas", quote_input(s)));
  return {static_cast<uint8_t>(v[0]), static_cast<uint8_t>(v[1]), static_cast<uint8_t>(v[2]), static_cast<uint8_t>(v[3])};
}

int32_t lod_q8(const char* option, double v) {
  if (!std::isfinite(v) || std::abs(v) > 1000.0)
    throw InputError(fmt::format("{} {} is not a finite value in [-1000, 1000]", option, v));
  return static_cast<int32_t>(float_to_fixed_round(static_cast<float>(v), 1, kLodFracBits));
}

}  // namespace

// "proc:NAME[:SIZE]" -> a procedural texture (default size 256); anything else is a file path.
Texture load_texture_spec(const std::string& spec) {
  const std::string prefix = "proc:";
  if (spec.rfind(prefix, 0) != 0) return load_texture(spec);
  std::string name = spec.substr(prefix.size());
  int size = 256;
  if (const auto colon = name.find(':'); colon != std::string::npos) {
    const std::string sz = name.substr(colon + 1);
    std::size_t used = 0;
    try {
      size = std::stoi(sz, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != sz.size() || sz.empty()) throw InputError(fmt::format("--texture '{}': size '{}' is not an integer", quote_input(spec), quote_input(sz)));
    name.resize(colon);
  }
  return make_procedural(name, size).texture;
}

Texture load_texture_from_options(const TextureOptions& o) {
  Texture tex = load_texture_spec(o.texture);
  if (o.format != "auto") {
    const TexelFormat f = texel_format_from_name(o.format);
    if (f == TexelFormat::L8)
      for (Image& l : tex.levels)
        for (Rgba8& t : l.texels) t = {t.r, t.r, t.r, 255};
    tex.format = f;
  }
  const std::string& m = o.mipmaps;
  if (m == "auto") {
    if (tex.levels.size() == 1) generate_mipmaps(tex, MipMethod::Box);
  } else if (m == "stored") {
    // keep what the file holds
  } else if (m == "none") {
    tex.levels.resize(1);
  } else {
    generate_mipmaps(tex, mip_method_from_name(m), o.alpha);
  }
  return tex;
}

SamplerConfig sampler_config_from_options(const SamplerOptions& o) {
  SamplerConfig c;
  c.mode = filter_mode_from_name(o.filter);
  c.wrap_s = wrap_mode_from_name(o.wrap_s.empty() ? o.wrap : o.wrap_s);
  c.wrap_t = wrap_mode_from_name(o.wrap_t.empty() ? o.wrap : o.wrap_t);
  c.border = parse_border(o.border);
  c.lod.bias_q8 = lod_q8("--lod-bias", o.lod_bias);
  c.lod.min_lod_q8 = lod_q8("--min-lod", o.min_lod);
  c.lod.max_lod_q8 = lod_q8("--max-lod", o.max_lod);
  try {
    c.kernel = checked_cubic_kernel_name(o.kernel);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--kernel: {}", e.what()));
  }
  c.cubic_rom.samples = o.rom_samples;
  c.cubic_rom.bits = o.rom_bits;
  c.cubic_rom.validate();
  c.cubic_recon = parse_choice<RomRecon>("--rom-recon", o.rom_recon, {{"nearest", RomRecon::Nearest}, {"linear", RomRecon::Linear}});
  c.edge_shape = parse_choice<EdgeShapePolicy>("--edge-shape", o.edge_shape,
                                               {{"cross", EdgeShapePolicy::Cross}, {"cache-block", EdgeShapePolicy::CacheBlock}});
  c.edge_cache_block = o.cache_block;
  return c;
}

}  // namespace tfu::cli
