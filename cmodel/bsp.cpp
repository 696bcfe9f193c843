#include "cmodel/bsp.hpp"

#include <bit>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/scene.hpp"

namespace tfu::q3 {
namespace {

static_assert(std::endian::native == std::endian::little, "the BSP reader assumes a little-endian host");

constexpr size_t kHeaderBytes = 8 + 8 * kLumpCount;
constexpr size_t kTextureRecord = 72, kVertexRecord = 44, kMeshvertRecord = 4, kFaceRecord = 104;
constexpr size_t kPlaneRecord = 16, kModelRecord = 40, kBrushRecord = 12, kBrushSideRecord = 8;
constexpr size_t kLightmapRecord = size_t{kLightmapSize} * kLightmapSize * 3;

// Little-endian field reads from a byte range already checked to be inside the file.
int32_t get_i32(const uint8_t* p) {
  int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}
float get_f32(const uint8_t* p) {
  float v;
  std::memcpy(&v, p, 4);
  return v;
}

class LumpReader {
 public:
  LumpReader(std::span<const uint8_t> file, const std::string& source) : file_(file), source_(source) {}

  [[noreturn]] void fail(int lump, const std::string& what) const {
    throw InputError(fmt::format("{}: lump {} ({}): {}", source_, lump, lump_name(lump), what));
  }

  void read_header() {
    if (file_.size() < kHeaderBytes)
      throw InputError(fmt::format("{}: {} bytes, too short for a BSP header ({} bytes)", source_, file_.size(), kHeaderBytes));
    if (std::memcmp(file_.data(), "IBSP", 4) != 0)
      throw InputError(fmt::format("{}: not a Quake III BSP (magic is not 'IBSP')", source_));
    const int32_t version = get_i32(file_.data() + 4);
    if (version != kBspVersion)
      throw InputError(fmt::format("{}: BSP version {}, expected {} (Quake III)", source_, version, kBspVersion));
    for (int k = 0; k < kLumpCount; ++k) {
      const int64_t offset = get_i32(file_.data() + 8 + 8 * k), length = get_i32(file_.data() + 12 + 8 * k);
      if (offset < 0 || length < 0 || offset + length > static_cast<int64_t>(file_.size()))
        fail(k, fmt::format("bytes {}+{} outside the {}-byte file", offset, length, file_.size()));
      lumps_[static_cast<size_t>(k)] = file_.subspan(static_cast<size_t>(offset), static_cast<size_t>(length));
    }
  }

  std::span<const uint8_t> lump(int k) const { return lumps_[static_cast<size_t>(k)]; }

  // Number of records of a lump of fixed-size records (whole records, at most kMaxBspRecords).
  size_t records(int k, size_t record_bytes) const {
    const size_t bytes = lump(k).size();
    if (bytes % record_bytes != 0) fail(k, fmt::format("{} bytes is not a whole number of {}-byte records", bytes, record_bytes));
    const size_t n = bytes / record_bytes;
    if (n > static_cast<size_t>(kMaxBspRecords)) fail(k, fmt::format("{} records, more than the limit {}", n, kMaxBspRecords));
    return n;
  }

 private:
  std::span<const uint8_t> file_;
  const std::string& source_;
  std::array<std::span<const uint8_t>, kLumpCount> lumps_{};
};

std::string read_entities(const LumpReader& r) {
  const auto bytes = r.lump(kLumpEntities);
  std::string text(bytes.begin(), bytes.end());
  if (const auto nul = text.find('\0'); nul != std::string::npos) text.resize(nul);
  return text;
}

std::vector<BspTexture> read_textures(const LumpReader& r) {
  const size_t n = r.records(kLumpTextures, kTextureRecord);
  std::vector<BspTexture> out(n);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = r.lump(kLumpTextures).data() + i * kTextureRecord;
    const char* name = reinterpret_cast<const char*>(p);
    out[i].name.assign(name, strnlen(name, 64));
    if (has_control_characters(out[i].name))  // never to reach a trace binding or a report
      r.fail(kLumpTextures, fmt::format("texture {} is named '{}', with a control character (names must be printable)", i,
                                        quote_input(out[i].name)));
    out[i].surface_flags = get_i32(p + 64);
    out[i].content_flags = get_i32(p + 68);
  }
  return out;
}

// [first, first + count) inside [0, size)?
bool range_inside(int64_t first, int64_t count, size_t size) {
  return first >= 0 && count >= 0 && first + count <= static_cast<int64_t>(size);
}

// A float of the collision lumps: finite and within the scene bound.
double checked_float(const LumpReader& r, int lump, size_t record, const uint8_t* p) {
  const double v = get_f32(p);
  if (!std::isfinite(v) || std::fabs(v) > kMaxSceneMagnitude)
    r.fail(lump, fmt::format("record {}: {:g} is not a finite number within +-{:g}", record, v, kMaxSceneMagnitude));
  return v;
}

void read_collision(const LumpReader& r, Bsp& bsp) {
  const size_t textures = bsp.textures.size();
  const size_t np = r.records(kLumpPlanes, kPlaneRecord);
  bsp.planes.resize(np);
  for (size_t i = 0; i < np; ++i) {
    const uint8_t* p = r.lump(kLumpPlanes).data() + i * kPlaneRecord;
    BspPlane& pl = bsp.planes[i];
    pl.normal = {checked_float(r, kLumpPlanes, i, p), checked_float(r, kLumpPlanes, i, p + 4),
                 checked_float(r, kLumpPlanes, i, p + 8)};
    pl.dist = checked_float(r, kLumpPlanes, i, p + 12);
    if (std::fabs(glm::length(pl.normal) - 1.0) > 1e-3)
      r.fail(kLumpPlanes, fmt::format("plane {}: normal of length {:g}, not a unit vector", i, glm::length(pl.normal)));
  }
  const size_t ns = r.records(kLumpBrushSides, kBrushSideRecord);
  bsp.brush_sides.resize(ns);
  for (size_t i = 0; i < ns; ++i) {
    const uint8_t* p = r.lump(kLumpBrushSides).data() + i * kBrushSideRecord;
    BspBrushSide& s = bsp.brush_sides[i];
    s.plane = get_i32(p);
    s.texture = get_i32(p + 4);
    if (!range_inside(s.plane, 1, np))
      r.fail(kLumpBrushSides, fmt::format("side {}: plane {} outside the {} of lump 2", i, s.plane, np));
    if (!range_inside(s.texture, 1, textures))
      r.fail(kLumpBrushSides, fmt::format("side {}: texture {} outside the {} of lump 1", i, s.texture, textures));
  }
  const size_t nb = r.records(kLumpBrushes, kBrushRecord);
  bsp.brushes.resize(nb);
  for (size_t i = 0; i < nb; ++i) {
    const uint8_t* p = r.lump(kLumpBrushes).data() + i * kBrushRecord;
    BspBrush& b = bsp.brushes[i];
    b.first_side = get_i32(p);
    b.side_count = get_i32(p + 4);
    b.texture = get_i32(p + 8);
    if (!range_inside(b.first_side, b.side_count, ns))
      r.fail(kLumpBrushes,
             fmt::format("brush {}: sides {}+{} outside the {} of lump 9", i, b.first_side, b.side_count, ns));
    if (!range_inside(b.texture, 1, textures))
      r.fail(kLumpBrushes, fmt::format("brush {}: texture {} outside the {} of lump 1", i, b.texture, textures));
  }
  const size_t nm = r.records(kLumpModels, kModelRecord);
  bsp.models.resize(nm);
  for (size_t i = 0; i < nm; ++i) {
    const uint8_t* p = r.lump(kLumpModels).data() + i * kModelRecord;
    BspModel& m = bsp.models[i];
    for (int k = 0; k < 3; ++k) {
      m.mins[k] = checked_float(r, kLumpModels, i, p + 4 * k);
      m.maxs[k] = checked_float(r, kLumpModels, i, p + 12 + 4 * k);
    }
    m.first_brush = get_i32(p + 32);
    m.brush_count = get_i32(p + 36);
    if (!range_inside(m.first_brush, m.brush_count, nb))
      r.fail(kLumpModels,
             fmt::format("model {}: brushes {}+{} outside the {} of lump 8", i, m.first_brush, m.brush_count, nb));
  }
}

// Fields 5 and 6 (lightmap s, t): q3map2 leaves NaN there on some vertices of vertex-lit faces.
constexpr bool is_lightmap_uv_field(size_t k) { return k == 5 || k == 6; }

void read_vertices(const LumpReader& r, Bsp& bsp) {
  const size_t n = r.records(kLumpVertices, kVertexRecord);
  std::vector<Vertex>& out = bsp.vertices;
  out.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = r.lump(kLumpVertices).data() + i * kVertexRecord;
    std::array<double, 10> f{};
    for (size_t k = 0; k < f.size(); ++k) {
      f[k] = get_f32(p + 4 * k);
      // The scene format's bound on coordinates holds here too: BSP floats have none, and a uv of 1e15 left
      // the ground truth's texel index outside int (TFU-S E17).
      if (std::isfinite(f[k]) && std::fabs(f[k]) <= kMaxSceneMagnitude) continue;
      if (!is_lightmap_uv_field(k))
        r.fail(kLumpVertices, fmt::format("vertex {}: field {} is not a finite number within +-{:g}: {:g}", i, k,
                                          kMaxSceneMagnitude, f[k]));
      f[k] = 0.0;
      if (bsp.nonfinite_lightmap_uv.empty()) bsp.nonfinite_lightmap_uv.resize(n, false);
      bsp.nonfinite_lightmap_uv[i] = true;
    }
    Vertex& v = out[i];
    v.pos = {f[0], f[1], f[2]};
    v.uv0 = {f[3], f[4]};
    v.uv1 = {f[5], f[6]};
    v.normal = {f[7], f[8], f[9]};
    std::memcpy(v.colour.data(), p + 40, 4);
  }
}

std::vector<int32_t> read_meshverts(const LumpReader& r) {
  const size_t n = r.records(kLumpMeshverts, kMeshvertRecord);
  std::vector<int32_t> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = get_i32(r.lump(kLumpMeshverts).data() + i * kMeshvertRecord);
  return out;
}

std::vector<std::vector<uint8_t>> read_lightmaps(const LumpReader& r) {
  const size_t n = r.records(kLumpLightmaps, kLightmapRecord);
  std::vector<std::vector<uint8_t>> out(n);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = r.lump(kLumpLightmaps).data() + i * kLightmapRecord;
    out[i].assign(p, p + kLightmapRecord);
  }
  return out;
}

BspFace decode_face(const uint8_t* p) {
  BspFace f;
  f.texture = get_i32(p);
  f.effect = get_i32(p + 4);
  f.type = static_cast<FaceType>(get_i32(p + 8));
  f.first_vertex = get_i32(p + 12);
  f.vertex_count = get_i32(p + 16);
  f.first_meshvert = get_i32(p + 20);
  f.meshvert_count = get_i32(p + 24);
  f.lightmap = get_i32(p + 28);
  f.patch_size = {get_i32(p + 96), get_i32(p + 100)};
  return f;
}

void check_patch_size(const LumpReader& r, size_t i, const BspFace& f) {
  const auto [w, h] = f.patch_size;
  const auto odd_in_range = [](int32_t s) { return s >= 3 && s <= kMaxPatchControlSize && s % 2 == 1; };
  if (!odd_in_range(w) || !odd_in_range(h))
    r.fail(kLumpFaces, fmt::format("face {}: patch of {}x{} control points (each side must be odd, 3..{})", i, w, h,
                                   kMaxPatchControlSize));
  if (int64_t{w} * h != f.vertex_count)
    r.fail(kLumpFaces, fmt::format("face {}: patch of {}x{} control points but {} vertices", i, w, h, f.vertex_count));
}

void check_meshverts(const LumpReader& r, size_t i, const BspFace& f, const std::vector<int32_t>& meshverts) {
  if (!range_inside(f.first_meshvert, f.meshvert_count, meshverts.size()))
    r.fail(kLumpFaces, fmt::format("face {}: meshverts {}+{} outside the {} of lump 11", i, f.first_meshvert,
                                   f.meshvert_count, meshverts.size()));
  if (f.meshvert_count % 3 != 0)
    r.fail(kLumpFaces, fmt::format("face {}: {} meshverts is not a whole number of triangles", i, f.meshvert_count));
  for (int32_t k = 0; k < f.meshvert_count; ++k) {
    const int32_t m = meshverts[static_cast<size_t>(f.first_meshvert + k)];
    if (m < 0 || m >= f.vertex_count)
      r.fail(kLumpMeshverts, fmt::format("meshvert {} (face {}) is {}, outside the face's {} vertices",
                                         f.first_meshvert + k, i, m, f.vertex_count));
  }
}

void check_face(const LumpReader& r, size_t i, const BspFace& f, const Bsp& bsp) {
  if (f.texture < 0 || static_cast<size_t>(f.texture) >= bsp.textures.size())
    r.fail(kLumpFaces, fmt::format("face {}: texture {} outside the {} of lump 1", i, f.texture, bsp.textures.size()));
  const auto type = static_cast<int32_t>(f.type);
  if (type < 1 || type > 4) r.fail(kLumpFaces, fmt::format("face {}: unknown type {} (1..4)", i, type));
  if (!range_inside(f.first_vertex, f.vertex_count, bsp.vertices.size()))
    r.fail(kLumpFaces, fmt::format("face {}: vertices {}+{} outside the {} of lump 10", i, f.first_vertex,
                                   f.vertex_count, bsp.vertices.size()));
  if (f.lightmap >= 0 && static_cast<size_t>(f.lightmap) >= bsp.lightmaps.size())
    r.fail(kLumpFaces, fmt::format("face {}: lightmap {} outside the {} of lump 14", i, f.lightmap, bsp.lightmaps.size()));
  if (f.lightmap >= 0 && !bsp.nonfinite_lightmap_uv.empty())
    for (int32_t k = 0; k < f.vertex_count; ++k)
      if (bsp.nonfinite_lightmap_uv[static_cast<size_t>(f.first_vertex + k)])
        r.fail(kLumpVertices, fmt::format("vertex {} (face {}, lightmap {}): lightmap uv is not a finite number within +-{:g}",
                                          f.first_vertex + k, i, f.lightmap, kMaxSceneMagnitude));
  if (f.type == FaceType::Patch) check_patch_size(r, i, f);
  if (f.type == FaceType::Polygon || f.type == FaceType::Mesh) check_meshverts(r, i, f, bsp.meshverts);
}

}  // namespace

const char* lump_name(int lump) {
  static constexpr const char* kNames[kLumpCount] = {
      "entities", "textures", "planes",    "nodes",   "leaves",    "leaf faces",   "leaf brushes", "models",    "brushes",
      "brush sides", "vertices", "meshverts", "effects", "faces", "lightmaps", "light volumes", "visibility"};
  return lump >= 0 && lump < kLumpCount ? kNames[lump] : "?";
}

Bsp parse_bsp(std::span<const uint8_t> file, const std::string& source) {
  LumpReader r(file, source);
  r.read_header();
  Bsp bsp;
  bsp.entities = read_entities(r);
  bsp.textures = read_textures(r);
  read_collision(r, bsp);
  read_vertices(r, bsp);
  bsp.meshverts = read_meshverts(r);
  bsp.lightmaps = read_lightmaps(r);
  const size_t n = r.records(kLumpFaces, kFaceRecord);
  bsp.faces.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    bsp.faces.push_back(decode_face(r.lump(kLumpFaces).data() + i * kFaceRecord));
    check_face(r, i, bsp.faces.back(), bsp);
  }
  return bsp;
}

// ---- Entities ----

std::string Entity::value(const std::string& key) const {
  for (auto it = keys.rbegin(); it != keys.rend(); ++it)
    if (it->first == key) return it->second;
  return {};
}

namespace {

// Tokens of the entity text: '{', '}', or a string (quoted, or a bare word); '//' comments to the
// end of the line are skipped.
class EntityLexer {
 public:
  EntityLexer(const std::string& text, const std::string& source) : text_(text), source_(source) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: lump 0 (entities): line {}: {}", source_, line_, what));
  }

  // Next token; false at the end of the text. `quoted` tells a quoted "{" from a brace.
  bool next(std::string& token, bool& quoted) {
    skip_space_and_comments();
    if (pos_ >= text_.size()) return false;
    quoted = text_[pos_] == '"';
    if (quoted) {
      const size_t end = text_.find('"', pos_ + 1);
      if (end == std::string::npos) fail("unterminated quoted string");
      token = text_.substr(pos_ + 1, end - pos_ - 1);
      if (token.find('\n') != std::string::npos) fail("line break inside a quoted string");
      pos_ = end + 1;
      return true;
    }
    if (text_[pos_] == '{' || text_[pos_] == '}') {
      token = text_.substr(pos_++, 1);
      return true;
    }
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '"' && text_[pos_] != '{' && text_[pos_] != '}') ++pos_;
    token = text_.substr(start, pos_ - start);
    return true;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void skip_space_and_comments() {
    while (pos_ < text_.size()) {
      if (text_[pos_] == '\n') ++line_;
      if (is_space(text_[pos_])) {
        ++pos_;
      } else if (text_.compare(pos_, 2, "//") == 0) {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  const std::string& text_;
  const std::string& source_;
  size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

std::vector<Entity> parse_entities(const std::string& text, const std::string& source) {
  EntityLexer lex(text, source);
  std::vector<Entity> out;
  std::string token, value;
  bool quoted = false;
  while (lex.next(token, quoted)) {
    if (quoted || token != "{") lex.fail(fmt::format("expected '{{', found '{}'", token.substr(0, 40)));
    Entity e;
    for (;;) {
      if (!lex.next(token, quoted)) lex.fail("text ends inside an entity");
      if (!quoted && token == "}") break;
      if (!quoted && token == "{") lex.fail("'{' inside an entity");
      if (!lex.next(value, quoted)) lex.fail(fmt::format("key '{}' has no value", token.substr(0, 40)));
      if (!quoted && (value == "{" || value == "}")) lex.fail(fmt::format("key '{}' has no value", token.substr(0, 40)));
      e.keys.emplace_back(token, value);
    }
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace tfu::q3
