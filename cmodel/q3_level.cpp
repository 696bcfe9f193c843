#include "cmodel/q3_level.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "cmodel/bezier_patch.hpp"
#include "cmodel/error.hpp"
#include "cmodel/q3_collision.hpp"

namespace tfu::q3 {
namespace {

// ---- Spawn points ----

// Whitespace-separated finite numbers of an entity value; nothing if any token is not one.
std::optional<std::vector<double>> parse_numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream words(text);
  std::string w;
  while (words >> w) {
    double v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc{} || end != w.data() + w.size() || !std::isfinite(v)) return std::nullopt;
    out.push_back(v);
  }
  return out;
}

// ---- Level assembly ----

class LevelBuilder {
 public:
  LevelBuilder(const Bsp& bsp, Level& level, TextureCache& cache) : bsp_(bsp), level_(level), cache_(cache) {}

  void add_textures() {
    for (const BspTexture& t : bsp_.textures) {
      LevelTexture lt;
      lt.name = t.name;
      lt.surface_flags = t.surface_flags;
      lt.surface = classify_surface(t);
      level_.textures.push_back(std::move(lt));
    }
  }

  void add_lightmaps() {
    for (const std::vector<uint8_t>& rgb : bsp_.lightmaps) {
      Texture tex;
      Image img(kLightmapSize, kLightmapSize);
      for (size_t i = 0; i < img.texels.size(); ++i) img.texels[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 255};
      tex.levels.push_back(std::move(img));
      level_.lightmaps.push_back(std::make_shared<const Texture>(std::move(tex)));
    }
    Texture white;
    white.levels.emplace_back(1, 1, Rgba8{255, 255, 255, 255});
    level_.white_lightmap = static_cast<int32_t>(level_.lightmaps.size());
    level_.lightmaps.push_back(std::make_shared<const Texture>(std::move(white)));
  }

  // Faces may share vertex ranges, so a small file could ask for any number of patch triangles:
  // the drawn faces' triangles are counted before anything is built.
  void check_triangle_budget() const {
    int64_t total = 0;
    for (size_t i = 0; i < bsp_.faces.size(); ++i) {
      const BspFace& f = bsp_.faces[i];
      if (f.type == FaceType::Billboard || level_.textures[static_cast<size_t>(f.texture)].surface != SurfaceClass::Drawn)
        continue;
      total += f.type == FaceType::Patch ? int64_t{2} * kPatchSubdivision * kPatchSubdivision *
                                               ((f.patch_size[0] - 1) / 2) * ((f.patch_size[1] - 1) / 2)
                                         : f.meshvert_count / 3;
      if (total > kMaxLevelTriangles)
        throw InputError(fmt::format("{}: lump 13 (faces): face {}: the level exceeds {} triangles", level_.source, i,
                                     kMaxLevelTriangles));
    }
  }

  void add_faces() {
    check_triangle_budget();
    level_.vertices = bsp_.vertices;
    LevelCounts& c = level_.counts;
    for (size_t i = 0; i < bsp_.faces.size(); ++i) {
      const BspFace& f = bsp_.faces[i];
      ++c.faces_by_type[static_cast<size_t>(f.type)];
      if (f.type == FaceType::Billboard) {
        ++c.billboards;
        continue;
      }
      LevelTexture& tex = level_.textures[static_cast<size_t>(f.texture)];
      if (tex.surface == SurfaceClass::Invisible) {
        ++c.skipped_invisible;
        continue;
      }
      if (tex.surface == SurfaceClass::Sky) {
        ++c.skipped_sky;
        continue;
      }
      add_face(static_cast<int32_t>(i), f, tex);
    }
    finish_counts();
  }

 private:
  void add_face(int32_t index, const BspFace& f, LevelTexture& tex) {
    if (!tex.texture) resolve(tex);
    LevelFace lf;
    lf.bsp_face = index;
    lf.type = f.type;
    lf.texture = f.texture;
    lf.lightmap = f.lightmap >= 0 ? f.lightmap : level_.white_lightmap;
    lf.first_triangle = static_cast<uint32_t>(level_.triangles.size());
    if (f.type == FaceType::Patch) {
      add_patch(f);
    } else {
      add_meshverts(f);
    }
    lf.triangle_count = static_cast<uint32_t>(level_.triangles.size()) - lf.first_triangle;
    level_.faces.push_back(lf);
    ++tex.faces_drawn;
    LevelCounts& c = level_.counts;
    ++c.faces_drawn;
    if (tex.fallback) ++c.fallback_faces;
    if (f.type == FaceType::Patch) ++c.patches;
    if (f.lightmap < 0) ++c.vertex_lit_faces;
  }

  // A texture is looked up (and decoded) when the first face drawn with it is added.
  void resolve(LevelTexture& tex) {
    const ResolvedTexture& r = cache_.get(tex.name);
    tex.texture = r.texture;
    tex.fallback = r.fallback;
    tex.source = r.source;
  }

  void add_meshverts(const BspFace& f) {
    const auto base = static_cast<uint32_t>(f.first_vertex);
    for (int32_t k = 0; k < f.meshvert_count; k += 3) {
      std::array<uint32_t, 3> tri{};
      for (size_t j = 0; j < 3; ++j)
        tri[j] = base + static_cast<uint32_t>(bsp_.meshverts[static_cast<size_t>(f.first_meshvert + k) + j]);
      level_.triangles.push_back(tri);
    }
  }

  void add_patch(const BspFace& f) {
    const std::span<const Vertex> control(bsp_.vertices.data() + f.first_vertex, static_cast<size_t>(f.vertex_count));
    const PatchMesh m = tessellate_patch(control, f.patch_size[0], f.patch_size[1]);
    const auto base = static_cast<uint32_t>(level_.vertices.size());
    level_.vertices.insert(level_.vertices.end(), m.vertices.begin(), m.vertices.end());
    for (const auto& t : m.triangles) level_.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }

  void finish_counts() {
    LevelCounts& c = level_.counts;
    for (const LevelTexture& t : level_.textures) {
      if (t.faces_drawn == 0) continue;
      ++(t.fallback ? c.fallback_textures : c.resolved_textures);
    }
    c.triangles = static_cast<int64_t>(level_.triangles.size());
    c.vertices = static_cast<int64_t>(level_.vertices.size());
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const auto& t : level_.triangles)
      for (uint32_t v : t) {
        lo = glm::min(lo, level_.vertices[v].pos);
        hi = glm::max(hi, level_.vertices[v].pos);
      }
    if (level_.triangles.empty()) lo = hi = glm::dvec3(0.0);
    level_.bounds_min = lo;
    level_.bounds_max = hi;
  }

  const Bsp& bsp_;
  Level& level_;
  TextureCache& cache_;
};

}  // namespace

std::vector<SpawnPoint> spawn_points(const std::vector<Entity>& entities, const std::string& classname,
                                     const std::string& source) {
  std::vector<SpawnPoint> out;
  for (size_t i = 0; i < entities.size(); ++i) {
    const Entity& e = entities[i];
    if (e.value("classname") != classname) continue;
    const auto fail = [&](const std::string& what) {
      throw InputError(fmt::format("{}: lump 0 (entities): entity {} ({}): {}", source, i, classname, what));
    };
    const auto origin = parse_numbers(e.value("origin"));
    if (!origin || origin->size() != 3) fail(fmt::format("\"origin\" \"{}\" is not 3 numbers", e.value("origin").substr(0, 60)));
    SpawnPoint s;
    s.origin = {(*origin)[0], (*origin)[1], (*origin)[2]};
    if (const std::string angle = e.value("angle"); !angle.empty()) {
      const auto a = parse_numbers(angle);
      if (!a || a->size() != 1) fail(fmt::format("\"angle\" \"{}\" is not a number", angle.substr(0, 60)));
      s.yaw_deg = (*a)[0];
    } else if (const std::string angles = e.value("angles"); !angles.empty()) {
      const auto a = parse_numbers(angles);
      if (!a || a->size() != 3) fail(fmt::format("\"angles\" \"{}\" is not 3 numbers", angles.substr(0, 60)));
      s.yaw_deg = (*a)[1];
    }
    out.push_back(s);
  }
  return out;
}

void place_spawns(const Bsp& bsp, std::vector<SpawnPoint>& spawns, int64_t* world_brushes) {
  const BrushWorld world(bsp, 0);
  if (world_brushes) *world_brushes = static_cast<int64_t>(world.brush_count());
  double floor_z = bsp.models.empty() ? 0.0 : bsp.models[0].mins.z;
  for (const Vertex& v : bsp.vertices) floor_z = std::min(floor_z, v.pos.z);
  floor_z -= 64.0;  // below everything: a drop that hits nothing ends here
  struct Box {
    glm::dvec3 lo, hi;
  };
  std::vector<Box> patches;
  for (const BspFace& f : bsp.faces) {
    if (f.type != FaceType::Patch ||
        (bsp.textures[static_cast<size_t>(f.texture)].content_flags & kMaskPlayerSolid) == 0)
      continue;
    Box b{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
    for (int32_t k = 0; k < f.vertex_count; ++k) {
      b.lo = glm::min(b.lo, bsp.vertices[static_cast<size_t>(f.first_vertex + k)].pos);
      b.hi = glm::max(b.hi, bsp.vertices[static_cast<size_t>(f.first_vertex + k)].pos);
    }
    patches.push_back(b);
  }
  for (SpawnPoint& s : spawns) {
    const SpawnRest r = spawn_rest(world, s.origin, floor_z);
    s.rest = r.origin;
    s.landed = r.landed;
    s.start_solid = r.start_solid;
    const double top = s.origin.z + kSpawnLift + kPlayerMaxs.z, feet = r.origin.z + kPlayerMins.z;
    s.patch_in_drop = false;
    for (const Box& b : patches)
      if (b.lo.x <= s.origin.x + kPlayerMaxs.x && b.hi.x >= s.origin.x + kPlayerMins.x &&
          b.lo.y <= s.origin.y + kPlayerMaxs.y && b.hi.y >= s.origin.y + kPlayerMins.y && b.hi.z >= feet &&
          b.lo.z <= top)
        s.patch_in_drop = true;
  }
}

std::vector<SpawnPoint> level_spawn_points(const Bsp& bsp, const std::string& source, std::string* spawn_class) {
  const std::vector<Entity> entities = parse_entities(bsp.entities, source);
  for (const char* classname : kSpawnClasses) {
    std::vector<SpawnPoint> spawns = spawn_points(entities, classname, source);
    if (spawns.empty()) continue;
    if (spawn_class) *spawn_class = classname;
    place_spawns(bsp, spawns, nullptr);
    return spawns;
  }
  return {};
}

Level build_level(const Bsp& bsp, const std::string& name, const std::string& source, TextureCache& cache) {
  Level level;
  level.name = name;
  level.source = source;
  level.spawns = level_spawn_points(bsp, source, &level.spawn_class);
  level.counts.world_brushes = bsp.models.empty() ? 0 : bsp.models[0].brush_count;
  LevelBuilder b(bsp, level, cache);
  b.add_textures();
  b.add_lightmaps();
  b.add_faces();
  return level;
}

Level load_level(const GameArchives& archives, const std::string& name, TextureCache& cache) {
  const EntryRef ref = archives.locate_level(name);
  const std::string source = archives.describe(ref);
  const std::vector<uint8_t> bytes = archives.read(ref);
  return build_level(parse_bsp(bytes, source), name, source, cache);
}

std::string level_summary(const Level& level) {
  const LevelCounts& c = level.counts;
  return fmt::format(
      "{}: {} textures ({} with images, {} fallback), {} lightmaps + white; faces: {} polygon, {} patch, {} mesh, "
      "{} billboard; {} drawn ({} with fallback, {} vertex-lit), skipped {} invisible, {} sky, {} billboard; "
      "{} triangles, {} vertices, {} spawn points ({})",
      level.name, level.textures.size(), c.resolved_textures, c.fallback_textures, level.lightmaps.size() - 1,
      c.faces_by_type[1], c.faces_by_type[2], c.faces_by_type[3], c.faces_by_type[4], c.faces_drawn, c.fallback_faces,
      c.vertex_lit_faces, c.skipped_invisible, c.skipped_sky, c.billboards, c.triangles, c.vertices, level.spawns.size(),
      level.spawn_class.empty() ? "none" : level.spawn_class);
}

std::vector<std::pair<std::string, int64_t>> level_count_fields(const Level& level) {
  const LevelCounts& c = level.counts;
  return {{"faces_polygon", c.faces_by_type[1]},
          {"faces_patch", c.faces_by_type[2]},
          {"faces_mesh", c.faces_by_type[3]},
          {"faces_billboard", c.faces_by_type[4]},
          {"faces_drawn", c.faces_drawn},
          {"skipped_invisible", c.skipped_invisible},
          {"skipped_sky", c.skipped_sky},
          {"fallback_faces", c.fallback_faces},
          {"fallback_textures", c.fallback_textures},
          {"resolved_textures", c.resolved_textures},
          {"patches", c.patches},
          {"vertex_lit_faces", c.vertex_lit_faces},
          {"triangles", c.triangles},
          {"vertices", c.vertices},
          {"lightmaps", static_cast<int64_t>(level.lightmaps.size()) - 1},
          {"spawn_points", static_cast<int64_t>(level.spawns.size())}};
}

}  // namespace tfu::q3
