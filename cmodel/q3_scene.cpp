#include "cmodel/q3_scene.hpp"

#include <charconv>
#include <map>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/q3_camera.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu::q3 {

bool is_level_scene(const std::string& scene) { return scene.starts_with(kLevelScenePrefix); }

LevelSceneSpec parse_level_scene(const std::string& scene, const std::string& option) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{} '{}': {} (expected oa:MAP[:SPAWN])", option, scene.substr(0, 80), what));
  };
  if (!is_level_scene(scene)) fail("not a level scene");
  const std::string rest = scene.substr(std::string(kLevelScenePrefix).size());
  LevelSceneSpec spec;
  const size_t colon = rest.find(':');
  spec.level = rest.substr(0, colon);
  if (spec.level.empty()) fail("no level name");
  if (spec.level.size() > kMaxLevelNameLength) fail(fmt::format("level name longer than {} characters", kMaxLevelNameLength));
  if (spec.level.find_first_of("/\\") != std::string::npos) fail("the level name contains a path separator");
  if (colon != std::string::npos) {
    const std::string n = rest.substr(colon + 1);
    const auto [end, ec] = std::from_chars(n.data(), n.data() + n.size(), spec.spawn);
    if (n.empty() || ec != std::errc{} || end != n.data() + n.size() || spec.spawn < 0)
      fail(fmt::format("spawn point '{}' is not a number >= 0", n.substr(0, 20)));
  }
  return spec;
}

Scene level_scene(const Level& level, int spawn, int width, int height, const UploadCompression& compress) {
  if (width < 1 || height < 1 || width > kMaxRenderSize || height > kMaxRenderSize)
    throw InputError(fmt::format("preview size {}x{} outside 1..{}", width, height, kMaxRenderSize));
  Scene scene;
  scene.name = fmt::format("oa-{}-{}", level.name, spawn);
  scene.description = level_summary(level);
  scene.width = width;
  scene.height = height;
  scene.camera = spawn_camera(level, spawn, width, height);
  scene.background = kLevelSceneBackground;

  std::map<std::pair<int32_t, int32_t>, size_t> mesh_of_material;  // (texture, light map) -> mesh
  std::vector<std::map<uint32_t, uint32_t>> remap;                  // per mesh: level vertex -> mesh vertex
  std::map<int32_t, std::string> compressed_as;                     // base texture -> its block format ("": none)
  for (const LevelFace& f : level.faces) {
    auto [it, added] = mesh_of_material.try_emplace({f.texture, f.lightmap}, scene.meshes.size());
    if (added) {
      const LevelTexture& t = level.textures[static_cast<size_t>(f.texture)];
      Mesh m;
      m.primitive = "bsp";
      TextureStage base;
      base.spec = {fmt::format("oa:{}:texture:{}", level.name, t.name), {}};
      base.texture = t.texture;
      if (compress.rule != UploadRule::None) {  // as the game uploads it; the trace binding says so too
        base.spec.params["compress"] = compress.name();
        base.texture = upload_compressed(t.texture, compress, base.spec.source);
        compressed_as[f.texture] = base.texture->compressed ? block_format_name(base.texture->compressed->image.format) : "";
      }
      base.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::Linear};
      base.sampler.wrap_s = base.sampler.wrap_t = WrapMode::Repeat;
      base.combine = {TexEnv::Replace, 1};
      TextureStage light;
      light.spec = {fmt::format("oa:{}:lightmap:{}", level.name, f.lightmap), {}};
      light.texture = level.lightmaps[static_cast<size_t>(f.lightmap)];
      light.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::None};
      light.sampler.wrap_s = light.sampler.wrap_t = WrapMode::ClampToEdge;
      light.uv_set = 1;
      light.combine = {TexEnv::Modulate, kLightmapOverbright};
      m.stages = {std::move(base), std::move(light)};
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
        if (fresh) mesh.vertices.push_back({level.vertices[v].pos, level.vertices[v].uv0, level.vertices[v].uv1});
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
