// Test data for the Quake III level loader, written by the tests themselves: a BSP file builder
// (IBSP 46, the lumps of cmodel/bsp.hpp), .pk3 archives through libzip, and TGA / JPEG images.
#pragma once

#include <zip.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "cmodel/bsp.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/texture.hpp"

namespace tfu::q3::testdata {

using Bytes = std::vector<uint8_t>;

inline void put_i32(Bytes& b, int32_t v) {
  uint8_t p[4];
  std::memcpy(p, &v, 4);
  b.insert(b.end(), p, p + 4);
}
inline void put_f32(Bytes& b, double v) {
  const auto f = static_cast<float>(v);
  uint8_t p[4];
  std::memcpy(p, &f, 4);
  b.insert(b.end(), p, p + 4);
}

struct FaceSpec {
  int32_t texture = 0;
  FaceType type = FaceType::Polygon;
  int32_t first_vertex = 0, vertex_count = 0, first_meshvert = 0, meshvert_count = 0;
  int32_t lightmap = -1;
  int32_t patch_w = 0, patch_h = 0;
};

// Builds a BSP file: lumps 0, 1, 2, 7, 8, 9, 10, 11, 13, 14 from the fields, the other lumps empty.
struct BspBuilder {
  std::string entities;
  std::vector<BspTexture> textures;
  std::vector<BspPlane> planes;
  std::vector<BspModel> models;
  std::vector<BspBrush> brushes;
  std::vector<BspBrushSide> brush_sides;
  std::vector<Vertex> vertices;
  std::vector<int32_t> meshverts;
  std::vector<FaceSpec> faces;
  std::vector<Bytes> lightmaps;  // each 128 x 128 x 3

  Bytes lump_bytes(int k) const {
    Bytes b;
    if (k == kLumpEntities) {
      b.assign(entities.begin(), entities.end());
      b.push_back(0);
    } else if (k == kLumpTextures) {
      for (const BspTexture& t : textures) {
        char name[64] = {};
        std::memcpy(name, t.name.data(), std::min<size_t>(t.name.size(), 63));
        b.insert(b.end(), name, name + 64);
        put_i32(b, t.surface_flags);
        put_i32(b, t.content_flags);
      }
    } else if (k == kLumpPlanes) {
      for (const BspPlane& p : planes)
        for (double f : {p.normal.x, p.normal.y, p.normal.z, p.dist}) put_f32(b, f);
    } else if (k == kLumpModels) {
      for (const BspModel& m : models) {
        for (double f : {m.mins.x, m.mins.y, m.mins.z, m.maxs.x, m.maxs.y, m.maxs.z}) put_f32(b, f);
        for (int32_t v : {0, 0, m.first_brush, m.brush_count}) put_i32(b, v);
      }
    } else if (k == kLumpBrushes) {
      for (const BspBrush& br : brushes)
        for (int32_t v : {br.first_side, br.side_count, br.texture}) put_i32(b, v);
    } else if (k == kLumpBrushSides) {
      for (const BspBrushSide& sd : brush_sides)
        for (int32_t v : {sd.plane, sd.texture}) put_i32(b, v);
    } else if (k == kLumpVertices) {
      for (const Vertex& v : vertices) {
        for (double f : {v.pos.x, v.pos.y, v.pos.z, v.uv0.x, v.uv0.y, v.uv1.x, v.uv1.y, v.normal.x, v.normal.y, v.normal.z})
          put_f32(b, f);
        b.insert(b.end(), v.colour.begin(), v.colour.end());
      }
    } else if (k == kLumpMeshverts) {
      for (int32_t m : meshverts) put_i32(b, m);
    } else if (k == kLumpFaces) {
      for (const FaceSpec& f : faces) {
        for (int32_t v : {f.texture, -1, static_cast<int32_t>(f.type), f.first_vertex, f.vertex_count, f.first_meshvert,
                          f.meshvert_count, f.lightmap, 0, 0, 0, 0})
          put_i32(b, v);
        for (int i = 0; i < 12; ++i) put_f32(b, 0.0);  // lightmap origin, vectors, normal: not read
        put_i32(b, f.patch_w);
        put_i32(b, f.patch_h);
      }
    } else if (k == kLumpLightmaps) {
      for (const Bytes& l : lightmaps) b.insert(b.end(), l.begin(), l.end());
    }
    return b;
  }

  // Adds a brush of texture `texture`: the box [lo, hi] (its six axial sides first, in q3map2's
  // order -x, +x, -y, +y, -z, +z) cut by further planes.
  int32_t add_brush(glm::dvec3 lo, glm::dvec3 hi, int32_t texture, const std::vector<BspPlane>& cuts = {}) {
    std::vector<BspPlane> sides = {{{-1, 0, 0}, -lo.x}, {{1, 0, 0}, hi.x},   {{0, -1, 0}, -lo.y},
                                   {{0, 1, 0}, hi.y},   {{0, 0, -1}, -lo.z}, {{0, 0, 1}, hi.z}};
    sides.insert(sides.end(), cuts.begin(), cuts.end());
    BspBrush br{static_cast<int32_t>(brush_sides.size()), static_cast<int32_t>(sides.size()), texture};
    for (const BspPlane& p : sides) {
      brush_sides.push_back({static_cast<int32_t>(planes.size()), texture});
      planes.push_back(p);
    }
    brushes.push_back(br);
    return static_cast<int32_t>(brushes.size()) - 1;
  }

  Bytes build(const char* magic = "IBSP", int32_t version = kBspVersion) const {
    Bytes out(magic, magic + 4);
    put_i32(out, version);
    Bytes body;
    std::array<std::pair<int32_t, int32_t>, kLumpCount> dir{};
    const auto header = static_cast<int32_t>(8 + 8 * kLumpCount);
    for (int k = 0; k < kLumpCount; ++k) {
      const Bytes b = lump_bytes(k);
      dir[static_cast<size_t>(k)] = {header + static_cast<int32_t>(body.size()), static_cast<int32_t>(b.size())};
      body.insert(body.end(), b.begin(), b.end());
    }
    for (const auto& [offset, length] : dir) {
      put_i32(out, offset);
      put_i32(out, length);
    }
    out.insert(out.end(), body.begin(), body.end());
    return out;
  }
};

// Rewrites directory entry k of a built BSP.
inline void set_lump(Bytes& bsp, int k, int32_t offset, int32_t length) {
  std::memcpy(bsp.data() + 8 + 8 * k, &offset, 4);
  std::memcpy(bsp.data() + 12 + 8 * k, &length, 4);
}
inline std::pair<int32_t, int32_t> get_lump(const Bytes& bsp, int k) {
  int32_t o, l;
  std::memcpy(&o, bsp.data() + 8 + 8 * k, 4);
  std::memcpy(&l, bsp.data() + 12 + 8 * k, 4);
  return {o, l};
}

using Entries = std::vector<std::pair<std::string, Bytes>>;

// Writes a zip archive with libzip (deflate, or stored when `store`).
inline void write_zip(const std::filesystem::path& path, const Entries& entries, bool store = false) {
  int err = 0;
  zip_t* za = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  ASSERT_NE(za, nullptr) << path;
  for (const auto& [name, bytes] : entries) {
    zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
    ASSERT_NE(src, nullptr);
    const zip_int64_t idx = zip_file_add(za, name.c_str(), src, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    ASSERT_GE(idx, 0) << zip_strerror(za);
    if (store) {
      ASSERT_EQ(zip_set_file_compression(za, static_cast<zip_uint64_t>(idx), ZIP_CM_STORE, 0), 0);
    }
  }
  ASSERT_EQ(zip_close(za), 0);
}

inline Bytes read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}
inline void write_file(const std::filesystem::path& path, const Bytes& b) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// An uncompressed 32-bit TGA of `rows` (row 0 = top of the image), stored bottom-up (the TGA
// default, origin bottom-left): the decoder must flip it.
inline Bytes make_tga(const std::vector<std::vector<Rgba8>>& rows) {
  const auto h = static_cast<uint16_t>(rows.size()), w = static_cast<uint16_t>(rows.front().size());
  Bytes b = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, static_cast<uint8_t>(w & 255), static_cast<uint8_t>(w >> 8),
             static_cast<uint8_t>(h & 255), static_cast<uint8_t>(h >> 8), 32, 8};
  for (size_t y = rows.size(); y-- > 0;)
    for (const Rgba8& p : rows[y]) b.insert(b.end(), {p.b, p.g, p.r, p.a});
  return b;
}

// A flat-colour JPEG of w x h written by OpenImageIO (through a scratch file).
inline Bytes make_jpeg(const std::filesystem::path& scratch, int w, int h, Rgba8 colour) {
  auto out = OIIO::ImageOutput::create(scratch.string());
  EXPECT_TRUE(out);
  if (!out) return {};
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> px;
  for (int i = 0; i < w * h; ++i) px.insert(px.end(), {colour.r, colour.g, colour.b});
  EXPECT_TRUE(out->open(scratch.string(), spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
  out->close();
  return read_file(scratch);
}

// A vertex with every attribute set.
inline Vertex vtx(glm::dvec3 pos, glm::dvec2 uv0, glm::dvec2 uv1 = {0, 0}, std::array<uint8_t, 4> colour = {255, 255, 255, 255},
                  glm::dvec3 normal = {0, 0, 1}) {
  Vertex v;
  v.pos = pos;
  v.uv0 = uv0;
  v.uv1 = uv1;
  v.normal = normal;
  v.colour = colour;
  return v;
}

// ---- The real game data, exactly the archives the tests were checked against ----
//
// The OpenArena tests' figures (level counts, texture sources, frame statistics) were counted on
// Debian's openarena-081-maps (pak1-maps.pk3, 50 levels) and openarena-081-textures
// (pak4-textures.pk3). Other archives installed in the same game directory change them: Debian's
// full `openarena` 0.8.8 adds archives that override 38 levels and at least 88 textures, and Quake
// III's search order lets the later archive win. So the tests read a private game directory of
// symbolic links to exactly these two archives of the installed one (q3::openarena_dir(): the
// Debian path or $TFU_OPENARENA_DIR), and give the same figures with or without the full game.
inline constexpr std::array<const char*, 2> kCheckedArchives = {"pak1-maps.pk3", "pak4-textures.pk3"};

class CheckedGameData {
 public:
  // Links the checked archives of `installed`; present() is false when one of them is missing.
  explicit CheckedGameData(const std::string& installed = openarena_dir()) : installed_(installed) {
    for (const char* name : kCheckedArchives) {
      const std::filesystem::path from = std::filesystem::path(installed) / name;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(from, ec)) return;
      std::filesystem::create_symlink(std::filesystem::absolute(from), dir_.path() / name, ec);
      if (ec) return;
    }
    present_ = true;
  }
  bool present() const { return present_; }
  // The private game directory (as --game-dir or SceneRequest::game_dir).
  std::string dir() const { return dir_.path().string(); }
  // For GTEST_SKIP when the data is not installed.
  std::string missing() const {
    return "OpenArena game data (" + std::string(kCheckedArchives[0]) + ", " + kCheckedArchives[1] + ") not installed in " +
           installed_;
  }

 private:
  std::string installed_;
  TempDir dir_{"tfu-game-data"};
  bool present_ = false;
};

// One private directory for the whole test program.
inline const CheckedGameData& checked_game_data() {
  static const CheckedGameData data;
  return data;
}

}  // namespace tfu::q3::testdata
