#include "cmodel/q3_scene.hpp"

#include <algorithm>
#include <charconv>
#include <map>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/q3_camera.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu::q3 {

bool is_level_scene(const std::string& scene) { return scene.starts_with(kLevelScenePrefix); }

int display_overbright_bits(const LevelSceneOptions& o) {
  return o.hardware_gamma ? std::clamp(o.overbright_bits, 0, kMaxDisplayShift) : 0;
}

int lighting_shift(const LevelSceneOptions& o) {
  return std::max(0, o.map_overbright_bits - display_overbright_bits(o));
}

Rgba8 shift_lighting(Rgba8 c, int shift) {
  uint32_t r = uint32_t{c.r} << shift, g = uint32_t{c.g} << shift, b = uint32_t{c.b} << shift;
  if ((r | g | b) > 255) {
    const uint32_t max = std::max({r, g, b});
    r = r * 255 / max;
    g = g * 255 / max;
    b = b * 255 / max;
  }
  return {static_cast<uint8_t>(r), static_cast<uint8_t>(g), static_cast<uint8_t>(b), c.a};
}

std::shared_ptr<const Texture> shifted_lightmap(const std::shared_ptr<const Texture>& lightmap, int shift) {
  if (shift == 0) return lightmap;
  Texture t = *lightmap;
  for (Image& level : t.levels)
    for (Rgba8& texel : level.texels) texel = shift_lighting(texel, shift);
  return std::make_shared<const Texture>(std::move(t));
}

std::shared_ptr<const Texture> srgb_declared(const std::shared_ptr<const Texture>& texture) {
  Texture t = *texture;
  t.format = TexelFormat::SRGBA8;
  generate_mipmaps(t, MipMethod::Box);  // keeps level 0, averages the others in linear light
  return std::make_shared<const Texture>(std::move(t));
}

namespace {

// KEY=VALUE of a level scene name into `o`; false for an unknown key or value.
bool set_scene_option(LevelSceneOptions& o, const std::string& key, const std::string& value) {
  const auto number = [&](int lo, int hi, int& out) {
    int v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || ec != std::errc{} || end != value.data() + value.size() || v < lo || v > hi) return false;
    out = v;
    return true;
  };
  const auto choice = [&](const char* a, const char* b, auto va, auto vb, auto& out) {
    if (value == a) return out = va, true;
    if (value == b) return out = vb, true;
    return false;
  };
  if (key == "eye") return choice("rest", "spot", EyeRule::Rest, EyeRule::Spot, o.eye);
  if (key == "light") return choice("game", "double", LightRule::Game, LightRule::Double, o.light);
  if (key == "vertex") return choice("colour", "white", VertexLight::Colour, VertexLight::White, o.vertex);
  if (key == "cull") return choice("back", "none", FaceCull::Back, FaceCull::None, o.cull);
  if (key == "gamma") return choice("hardware", "none", true, false, o.hardware_gamma);
  if (key == "srgb") return choice("false", "true", false, true, o.srgb_textures);
  if (key == "mapoverbright") return number(0, kMaxLightingShift, o.map_overbright_bits);
  if (key == "overbright") return number(0, kMaxDisplayShift, o.overbright_bits);
  return false;
}

}  // namespace

LevelSceneSpec parse_level_scene(const std::string& scene, const std::string& option) {
  const auto fail = [&](const std::string& what) {
    throw InputError(
        fmt::format("{} '{}': {} (expected oa:MAP[:SPAWN][:KEY=VALUE...])", option, scene.substr(0, 60), what));
  };
  if (!is_level_scene(scene)) fail("not a level scene");
  const std::string rest = scene.substr(std::string(kLevelScenePrefix).size());
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t colon = rest.find(':', start);
    parts.push_back(rest.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  LevelSceneSpec spec;
  spec.level = parts[0];
  if (spec.level.empty()) fail("no level name");
  if (spec.level.size() > kMaxLevelNameLength) fail(fmt::format("level name longer than {} characters", kMaxLevelNameLength));
  if (spec.level.find_first_of("/\\") != std::string::npos) fail("the level name contains a path separator");
  size_t k = 1;
  if (parts.size() > 1 && parts[1].find('=') == std::string::npos) {
    const std::string& n = parts[1];
    const auto [end, ec] = std::from_chars(n.data(), n.data() + n.size(), spec.spawn);
    if (n.empty() || ec != std::errc{} || end != n.data() + n.size() || spec.spawn < 0)
      fail(fmt::format("spawn point '{}' is not a number >= 0", n.substr(0, 20)));
    k = 2;
  }
  for (; k < parts.size(); ++k) {
    const size_t eq = parts[k].find('=');
    if (eq == std::string::npos || !set_scene_option(spec.options, parts[k].substr(0, eq), parts[k].substr(eq + 1)))
      fail(
          fmt::format("unknown option '{}' (eye=rest|spot, light=game|double, vertex=colour|white, cull=back|none, "
                      "mapoverbright=0..{}, overbright=0..{}, gamma=hardware|none, srgb=false|true)",
                      parts[k].substr(0, 20), kMaxLightingShift, kMaxDisplayShift));
  }
  return spec;
}

Scene level_scene(const Level& level, int spawn, int width, int height, const LevelSceneOptions& options,
                  const UploadCompression& compress) {
  if (width < 1 || height < 1 || width > kMaxRenderSize || height > kMaxRenderSize)
    throw InputError(fmt::format("preview size {}x{} outside 1..{}", width, height, kMaxRenderSize));
  Scene scene;
  scene.name = fmt::format("oa-{}-{}", level.name, spawn);
  scene.description = level_summary(level);
  scene.width = width;
  scene.height = height;
  scene.camera = spawn_camera(level, spawn, width, height, options.eye);
  scene.background = kLevelSceneBackground;
  const bool game_light = options.light == LightRule::Game;
  const int shift = game_light ? lighting_shift(options) : 0;
  scene.display_shift = game_light ? display_overbright_bits(options) : 0;
  scene.cull = options.cull == FaceCull::Back ? CullWinding::CounterClockwise : CullWinding::None;
  // Vertex-lit faces by their vertex colour (one stage) unless asked for the white light map.
  const bool by_vertex = options.vertex == VertexLight::Colour;
  std::map<int32_t, std::shared_ptr<const Texture>> lightmaps;  // shifted once per scene
  const auto lightmap = [&](int32_t index) {
    auto& t = lightmaps[index];
    if (!t)
      t = shifted_lightmap(level.lightmaps[static_cast<size_t>(index)], index == level.white_lightmap ? 0 : shift);
    return t;
  };
  const std::string lightmap_kind = shift == 0 ? "lightmap" : fmt::format("lightmap-shift{}", shift);

  std::map<std::pair<int32_t, int32_t>, size_t> mesh_of_material;  // (texture, light map) -> mesh
  std::vector<std::map<uint32_t, uint32_t>> remap;                  // per mesh: level vertex -> mesh vertex
  std::map<int32_t, std::string> compressed_as;                     // base texture -> its block format ("": none)
  std::map<int32_t, std::shared_ptr<const Texture>> declared_srgb;  // base texture -> its srgba8 form, made once
  for (const LevelFace& f : level.faces) {
    auto [it, added] = mesh_of_material.try_emplace({f.texture, f.lightmap}, scene.meshes.size());
    if (added) {
      const LevelTexture& t = level.textures[static_cast<size_t>(f.texture)];
      Mesh m;
      m.primitive = "bsp";
      TextureStage base;
      base.spec = {fmt::format("oa:{}:texture:{}", level.name, t.name), {}};
      base.texture = t.texture;
      if (options.srgb_textures) {  // the trace binding says so too (load_texture_spec)
        base.spec.params["srgb"] = "true";
        auto& declared = declared_srgb[f.texture];
        if (!declared) declared = srgb_declared(t.texture);
        base.texture = declared;
      }
      if (compress.rule != UploadRule::None) {  // as the game uploads it; the trace binding says so too
        base.spec.params["compress"] = compress.name();
        base.texture = upload_compressed(base.texture, compress, base.spec.source);
        compressed_as[f.texture] = base.texture->compressed ? block_format_name(base.texture->compressed->image.format) : "";
      }
      base.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::Linear};
      base.sampler.wrap_s = base.sampler.wrap_t = WrapMode::Repeat;
      base.combine = {TexEnv::Replace, 1};
      if (by_vertex && f.lightmap == level.white_lightmap) {
        base.combine = {TexEnv::Modulate, 1};  // rgbGen exactVertex: base x vertex colour
        m.vertex_colour = true;
        m.stages = {std::move(base)};
      } else {
        TextureStage light;
        light.spec = {fmt::format("oa:{}:{}:{}", level.name,
                                  f.lightmap == level.white_lightmap ? "lightmap" : lightmap_kind, f.lightmap),
                      {}};
        light.texture = lightmap(f.lightmap);
        light.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::None};
        light.sampler.wrap_s = light.sampler.wrap_t = WrapMode::ClampToEdge;
        light.uv_set = 1;
        light.combine = {TexEnv::Modulate, game_light ? 1 : kLightmapOverbright};
        m.stages = {std::move(base), std::move(light)};
      }
      scene.meshes.push_back(std::move(m));
      remap.emplace_back();
    }
    Mesh& mesh = scene.meshes[it->second];
    auto& vmap = remap[it->second];
    for (uint32_t k = 0; k < f.triangle_count; ++k) {
      std::array<uint32_t, 3> tri{};
      for (size_t j = 0; j < 3; ++j) {
        const uint32_t v = level.triangles[f.first_triangle + k][j];
        auto [vit, fresh] = vmap.try_emplace(v, static_cast<uint32_t>(mesh.vertices.size()));
        if (fresh) {
          const q3::Vertex& lv = level.vertices[v];
          // Alpha 255: the default shaders draw opaque (GLS_DEFAULT, no blending), so the frame is too.
          const Rgba8 colour{lv.colour[0], lv.colour[1], lv.colour[2], 255};
          mesh.vertices.push_back({lv.pos, lv.uv0, lv.uv1, shift_lighting(colour, shift)});
        }
        tri[j] = vit->second;
      }
      mesh.triangles.push_back(tri);
    }
  }
  if (compress.rule != UploadRule::None) {
    std::map<std::string, int> count;  // format name -> textures
    for (const auto& [texture, format] : compressed_as) ++count[format];
    std::string list;
    for (const auto& [format, n] : count)
      list += fmt::format("{}{} {}", list.empty() ? "" : ", ", n, format.empty() ? "uncompressed" : format);
    scene.description += fmt::format("; textures compressed at upload ({}): {}; light maps uncompressed", compress.name(), list);
  }
  return scene;
}

}  // namespace tfu::q3
