#include "cmodel/bindings.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "cmodel/block_formats.hpp"
#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu {

namespace {

long parse_int(const std::string& v, long lo, long hi) {
  char* end = nullptr;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || end != v.c_str() + v.size() || x < lo || x > hi)
    throw InputError(fmt::format("'{}' is not an integer {}..{}", quote_input(v), lo, hi));
  return x;
}

// A LOD register value: decimal levels within +-1000, rounded to the nearest 1/256 (Q.8).
int32_t parse_lod(const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || end != v.c_str() + v.size() || !std::isfinite(x) || std::abs(x) > 1000.0 ||
      v.find_first_of("xXpP") != std::string::npos)
    throw InputError(fmt::format("'{}' is not a decimal number of levels within -1000..1000", quote_input(v)));
  return static_cast<int32_t>(float_to_fixed_round(static_cast<float>(x), 1, kLodFracBits));
}
std::string lod_string(int32_t q8) { return fmt::format("{:.9g}", q8 / 256.0); }

bool parse_bool(const std::string& v) {
  if (v == "true" || v == "1") return true;
  if (v == "false" || v == "0") return false;
  throw InputError(fmt::format("'{}' is not true or false", quote_input(v)));
}

template <class E>
E pick(const std::string& v, std::initializer_list<std::pair<const char*, E>> choices) {
  std::string list;
  for (const auto& [name, e] : choices) {
    if (v == name) return e;
    list += (list.empty() ? "" : ", ") + std::string(name);
  }
  throw InputError(fmt::format("'{}' is not one of {}", quote_input(v), list));
}
template <class E>
std::string name_of(E e, std::initializer_list<std::pair<const char*, E>> choices) {
  for (const auto& [name, x] : choices)
    if (x == e) return name;
  return "?";
}

Rgba8 parse_border(const std::string& s) {
  int v[4];
  size_t n = 0, p = 0;
  while (true) {
    const size_t c = s.find(',', p);
    if (n == 4) n = 5;
    else v[n++] = static_cast<int>(parse_int(s.substr(p, c == std::string::npos ? std::string::npos : c - p), 0, 255));
    if (c == std::string::npos) break;
    p = c + 1;
  }
  if (n != 4) throw InputError(fmt::format("'{}' is not four integers 0..255 separated by commas", quote_input(s)));
  return {static_cast<uint8_t>(v[0]), static_cast<uint8_t>(v[1]), static_cast<uint8_t>(v[2]), static_cast<uint8_t>(v[3])};
}

const std::initializer_list<std::pair<const char*, RomRecon>> kRecon{{"nearest", RomRecon::Nearest}, {"linear", RomRecon::Linear}};
const std::initializer_list<std::pair<const char*, SamplePos>> kRomPos{{"centre", SamplePos::Centre}, {"corner", SamplePos::Corner}};
const std::initializer_list<std::pair<const char*, RomRounding>> kRounding{{"sum-preserving", RomRounding::SumPreserving},
                                                                           {"nearest", RomRounding::Nearest}};
const std::initializer_list<std::pair<const char*, AnisoRounding>> kAnisoRounding{{"integer", AnisoRounding::Integer},
                                                                                  {"pow2", AnisoRounding::PowerOfTwo}};
const std::initializer_list<std::pair<const char*, AnisoAxes>> kAnisoAxes{{"screen", AnisoAxes::Screen},
                                                                          {"ellipse", AnisoAxes::Ellipse}};

using SD = SamplerDescriptor;
const SamplerParam kSamplerParams[] = {
    {"filter", "filter mode (GL name, or bilinear / trilinear)",
     [](SD& s, const std::string& v) { s.mode = filter_mode_from_name(v); }, [](const SD& s) { return filter_mode_name(s.mode); }},
    {"wrap_s", "repeat, mirrored-repeat, clamp-to-edge, clamp-to-border",
     [](SD& s, const std::string& v) { s.wrap_s = wrap_mode_from_name(v); }, [](const SD& s) { return std::string(wrap_mode_name(s.wrap_s)); }},
    {"wrap_t", "as wrap_s", [](SD& s, const std::string& v) { s.wrap_t = wrap_mode_from_name(v); },
     [](const SD& s) { return std::string(wrap_mode_name(s.wrap_t)); }},
    {"border", "border texel word r,g,b,a (0..255 each)", [](SD& s, const std::string& v) { s.border = parse_border(v); },
     [](const SD& s) { return fmt::format("{},{},{},{}", s.border.r, s.border.g, s.border.b, s.border.a); }},
    {"lod_bias", "LOD bias, levels", [](SD& s, const std::string& v) { s.lod.bias_q8 = parse_lod(v); },
     [](const SD& s) { return lod_string(s.lod.bias_q8); }},
    {"min_lod", "lower clamp of lambda, levels", [](SD& s, const std::string& v) { s.lod.min_lod_q8 = parse_lod(v); },
     [](const SD& s) { return lod_string(s.lod.min_lod_q8); }},
    {"max_lod", "upper clamp of lambda, levels", [](SD& s, const std::string& v) { s.lod.max_lod_q8 = parse_lod(v); },
     [](const SD& s) { return lod_string(s.lod.max_lod_q8); }},
    {"kernel", "CUBIC kernel: box, tent, bspline, catmull-rom, mitchell, kaiser, blackman, bspline-interp",
     [](SD& s, const std::string& v) {
       cubic_kernel_index(v);
       s.kernel = v;
     },
     [](const SD& s) { return s.kernel; }},
    {"rom_samples", "CUBIC weight ROM: samples per tile (16..512)",
     [](SD& s, const std::string& v) { s.cubic_rom.samples = static_cast<int>(parse_int(v, TileRomSpec::kMinSamples, TileRomSpec::kMaxSamples)); },
     [](const SD& s) { return std::to_string(s.cubic_rom.samples); }},
    {"rom_bits", "CUBIC weight ROM: magnitude bits (4..16)",
     [](SD& s, const std::string& v) { s.cubic_rom.bits = static_cast<unsigned>(parse_int(v, TileRomSpec::kMinBits, TileRomSpec::kMaxBits)); },
     [](const SD& s) { return std::to_string(s.cubic_rom.bits); }},
    {"rom_pos", "CUBIC weight ROM sample positions: centre or corner",
     [](SD& s, const std::string& v) { s.cubic_rom.pos = pick(v, kRomPos); }, [](const SD& s) { return name_of(s.cubic_rom.pos, kRomPos); }},
    {"rom_rounding", "CUBIC weight ROM rounding: sum-preserving or nearest",
     [](SD& s, const std::string& v) { s.cubic_rom.rounding = pick(v, kRounding); },
     [](const SD& s) { return name_of(s.cubic_rom.rounding, kRounding); }},
    {"rom_recon", "CUBIC weights between ROM entries: nearest or linear",
     [](SD& s, const std::string& v) { s.cubic_recon = pick(v, kRecon); }, [](const SD& s) { return name_of(s.cubic_recon, kRecon); }},
    {"level_adapt", "CUBIC kernel fitted to each MIP level: true or false",
     [](SD& s, const std::string& v) { s.cubic_level_adapt = parse_bool(v); },
     [](const SD& s) { return std::string(s.cubic_level_adapt ? "true" : "false"); }},
    {"edge_shape", "EDGE_PRESERVING kernel shapes: static, cross or cache-aware",
     [](SD& s, const std::string& v) { s.edge_shape = edge_shape_from_name(v); },
     [](const SD& s) { return std::string(edge_shape_name(s.edge_shape)); }},
    {"max_aniso", "maximum anisotropy, probes per pixel (1..16)",
     [](SD& s, const std::string& v) { s.max_aniso = static_cast<int>(parse_int(v, 1, 16)); },
     [](const SD& s) { return std::to_string(s.max_aniso); }},
    {"aniso_rounding", "probe count: integer or pow2",
     [](SD& s, const std::string& v) { s.aniso_rounding = pick(v, kAnisoRounding); },
     [](const SD& s) { return name_of(s.aniso_rounding, kAnisoRounding); }},
    {"aniso_threshold", "probe threshold in eighths of Pmin (0..7; 0 the spec's N)",
     [](SD& s, const std::string& v) { s.aniso_threshold = static_cast<int>(parse_int(v, 0, kAnisoThresholdMax)); },
     [](const SD& s) { return std::to_string(s.aniso_threshold); }},
    {"aniso_axes", "axis lengths: screen (the spec's Px, Py) or ellipse (the footprint's true axes)",
     [](SD& s, const std::string& v) { s.aniso_axes = pick(v, kAnisoAxes); },
     [](const SD& s) { return name_of(s.aniso_axes, kAnisoAxes); }},
};

constexpr const char* kTextureParamKeys[] = {"format", "mipmaps", "alpha", "layout", "tile_bytes", "compress", "srgb"};

}  // namespace

std::span<const SamplerParam> sampler_params() { return kSamplerParams; }

void set_sampler_param(SamplerDescriptor& s, const std::string& key, const std::string& value) {
  for (const SamplerParam& q : kSamplerParams)
    if (key == q.key) return q.set(s, value);
  std::vector<std::string> keys;
  for (const SamplerParam& q : kSamplerParams) keys.emplace_back(q.key);
  const std::string hint = did_you_mean(key, keys);
  throw InputError(fmt::format("unknown sampler key '{}'{}", quote_input(key), hint.empty() ? "" : " (" + hint.substr(0, hint.size() - 1) + ")"));
}

SamplerDescriptor sampler_from_params(const Params& params, const std::string& where, SamplerDescriptor s) {
  for (const auto& [key, value] : params) {
    try {
      set_sampler_param(s, key, value);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      throw InputError(msg.rfind("unknown sampler key", 0) == 0 ? fmt::format("{}: {}", where, msg)
                                                                 : fmt::format("{}: key '{}': {}", where, key, msg));
    }
  }
  try {
    s.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  return s;
}

Params sampler_to_params(const SamplerDescriptor& s) {
  Params p;
  for (const SamplerParam& q : kSamplerParams) p[q.key] = q.get(s);
  return p;
}

std::span<const char* const> texture_param_keys() { return kTextureParamKeys; }

Texture texture_with_params(Texture tex, const Params& params, const std::string& where) {
  for (const auto& [key, value] : params) {
    bool known = false;
    for (const char* k : kTextureParamKeys) known = known || key == k;
    if (!known) throw InputError(fmt::format("{}: unknown texture key '{}'", where, quote_input(key)));
  }
  const auto param = [&params](const char* key, const char* def) {
    const auto it = params.find(key);
    return it == params.end() ? std::string(def) : it->second;
  };
  const auto fail = [&where](const std::string& key, const std::string& msg) -> InputError {
    return InputError(fmt::format("{}: key '{}': {}", where, key, msg));
  };
  if (tex.compressed) {  // a DDS, KTX or .astc file: its format and levels are the file's
    for (const char* key : {"format", "mipmaps", "alpha"})
      if (params.contains(key) && !(std::string(key) == "mipmaps" && (param(key, "") == "auto" || param(key, "") == "stored")))
        throw fail(key, "a compressed file's texels and MIP levels are its own (the key applies to uncompressed images)");
  }
  const std::string format = param("format", "auto");
  if (format != "auto") {
    TexelFormat f{};
    try {
      f = texel_format_from_name(format);
    } catch (const InputError& e) {
      throw fail("format", e.what());
    }
    if (f == TexelFormat::L8)
      for (Image& l : tex.levels)
        for (Rgba8& t : l.texels) t = {t.r, t.r, t.r, 255};
    tex.format = f;
  }
  // srgb=true: R, G, B hold sRGB codes (srgba8: decoded to linear before filtering, docs/srgb.md);
  // set before the MIP levels are made so that they are averaged in linear, as GL's sRGB mipmaps.
  bool srgb = false;
  try {
    srgb = parse_bool(param("srgb", "false"));
  } catch (const InputError& e) {
    throw fail("srgb", e.what());
  }
  if (srgb) {
    if (tex.format == TexelFormat::VS16X2) throw fail("srgb", "a vs16x2 texture holds signed numbers, not colours");
    tex.format = TexelFormat::SRGBA8;  // an l8 texture's words are (L, L, L, 255) already
  }
  try {
    tex.layout = memory_layout_from_name(param("layout", "tiled"));
  } catch (const InputError& e) {
    throw fail("layout", e.what());
  }
  try {
    tex.tile_bytes = static_cast<int>(parse_int(param("tile_bytes", "64"), 64, 1024));
  } catch (const InputError& e) {
    throw fail("tile_bytes", e.what());
  }
  if (!valid_tile_bytes(tex.tile_bytes)) throw fail("tile_bytes", "must be 64, 256 or 1024");
  double alpha = 0.5;
  if (params.contains("alpha")) {
    char* end = nullptr;
    const std::string& a = params.at("alpha");
    alpha = std::strtod(a.c_str(), &end);
    if (a.empty() || end != a.c_str() + a.size() || !(alpha >= 0.0 && alpha <= 1.0)) throw fail("alpha", "must be a number in 0..1");
  }
  const std::string m = param("mipmaps", "auto");
  try {
    if (tex.compressed) {
      // the file's levels, as stored
    } else if (m == "auto") {
      if (tex.levels.size() == 1) generate_mipmaps(tex, MipMethod::Box);
    } else if (m == "stored") {
      // keep what the file holds
    } else if (m == "none") {
      tex.levels.resize(1);
    } else {
      generate_mipmaps(tex, mip_method_from_name(m), alpha);
    }
  } catch (const InputError& e) {
    throw fail("mipmaps", e.what());
  }
  // compress=FORMAT: the levels encoded as a driver would at upload (cmodel/block_encode.hpp) and the
  // texture then held as blocks: texture memory stores them, the unit decodes them (docs/compressed.md).
  const std::string compress = param("compress", "none");
  if (compress != "none") {
    if (tex.compressed) throw fail("compress", "the file is compressed already");
    try {
      if (const std::optional<BlockFormat> f = upload_block_format(upload_compression_from_name(compress), tex))
        tex = compress_texture(tex, *f, where);
    } catch (const InputError& e) {
      throw fail("compress", e.what());
    }
  }
  return tex;
}

LoadedTexture load_texture_spec(const TextureSpec& spec, const std::string& where, const std::string& base_dir,
                                const std::string& game_dir) {
  for (const auto& [key, value] : spec.params) {
    bool known = false;
    for (const char* k : kTextureParamKeys) known = known || key == k;
    if (!known) throw InputError(fmt::format("{}: unknown texture key '{}'", where, quote_input(key)));
  }
  LoadedTexture out;
  if (spec.source.rfind(q3::kLevelScenePrefix, 0) == 0) {  // a texture or light map of a game level
    // A level's texture as the game uploads it: the keys are compress (a level run's --compress) and,
    // on base textures, srgb (the level option srgb=true). Light maps stay linear (q3::LevelSceneOptions).
    for (const auto& [key, value] : spec.params)
      if (key != "compress" && key != "srgb")
        throw InputError(fmt::format("{}: a level's texture takes no key but compress and srgb", where));
    bool srgb = false;
    if (const auto it = spec.params.find("srgb"); it != spec.params.end()) {
      try {
        srgb = parse_bool(it->second);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: key 'srgb': {}", where, e.what()));
      }
      const std::string rest = spec.source.substr(std::string(q3::kLevelScenePrefix).size());  // MAP:KIND:...
      const size_t colon = rest.find(':');
      if (srgb && colon != std::string::npos && rest.compare(colon + 1, 8, "texture:") != 0)
        throw InputError(
            fmt::format("{}: key 'srgb': a level's light maps hold linear light and cannot be declared sRGB", where));
    }
    out.texture = level_texture(spec.source, where, game_dir);
    if (srgb) out.texture = q3::srgb_declared(out.texture);
    if (const auto it = spec.params.find("compress"); it != spec.params.end()) {
      try {
        out.texture = upload_compressed(out.texture, upload_compression_from_name(it->second), where);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: key 'compress': {}", where, e.what()));
      }
    }
    return out;
  }
  Texture tex;
  const std::string prefix = "proc:";
  if (spec.source.rfind(prefix, 0) == 0) {
    std::string name = spec.source.substr(prefix.size());
    int size = 256;
    if (const auto colon = name.find(':'); colon != std::string::npos) {
      try {
        size = static_cast<int>(parse_int(name.substr(colon + 1), 1, kMaxTextureSize));
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}: texture '{}': size {}", where, quote_input(spec.source), e.what()));
      }
      name.resize(colon);
    }
    try {
      Procedural p = make_procedural(name, size);
      tex = std::move(p.texture);
      out.truth = std::move(p.eval);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", where, e.what()));
    }
  } else {
    std::filesystem::path path(spec.source);
    if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
    try {
      tex = load_texture(path.string());  // its errors name the file ...
    } catch (const InputError& e) {
      // ... and `where` the scene key, trace line or option that named it (TFU-S E13)
      throw InputError(fmt::format("{}: {}", where, e.what()));
    }
  }
  out.texture = std::make_shared<const Texture>(texture_with_params(std::move(tex), spec.params, where));
  return out;
}

}  // namespace tfu
