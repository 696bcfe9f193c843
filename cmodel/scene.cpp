#include "cmodel/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_input.hpp"
#include "cmodel/json_keys.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/mipmap.hpp"

#include "cmodel/embedded_scenes.hpp"

namespace tfu {
namespace {

using nlohmann::json;

// ---- Checked access to one JSON object: every key must be known, every value of the right type ----
class Obj {
 public:
  Obj(const json& j, std::string path, const std::string& source, const std::set<std::string>& allowed)
      : j_(j), path_(std::move(path)), source_(source) {
    if (!j.is_object()) fail(fmt::format("expected an object, got {}", j.type_name()));
    if (const auto key = first_unknown_key(j, allowed)) fail(unknown_key_text(*key));
  }

  [[noreturn]] void fail(const std::string& msg) const { throw InputError(where(path_, msg)); }
  [[noreturn]] void fail_key(const std::string& key, const std::string& msg) const {
    throw InputError(where(child(key), msg));
  }
  std::string where(const std::string& path, const std::string& msg) const {
    return path.empty() ? fmt::format("{}: {}", source_, msg) : fmt::format("{}: {}: {}", source_, path, msg);
  }
  std::string child(const std::string& key) const { return path_.empty() ? key : fmt::format("{}.{}", path_, key); }
  // "FILE: PATH" of a key path, the prefix of this object's error messages.
  std::string location(const std::string& path) const { return path.empty() ? source_ : fmt::format("{}: {}", source_, path); }
  const std::string& source() const { return source_; }

  bool has(const std::string& key) const { return j_.contains(key); }
  const json& raw(const std::string& key) const { return j_.at(key); }

  double number(const std::string& key, double def) const {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_number()) fail_key(key, fmt::format("expected a number, got {}", v.type_name()));
    const auto d = v.get<double>();
    if (!std::isfinite(d) || std::fabs(d) > kMaxSceneMagnitude)
      fail_key(key, fmt::format("expected a finite number within +-{:g}, got {}", kMaxSceneMagnitude, json_number_text(v)));
    return d;
  }
  int integer(const std::string& key, int def, int lo, int hi) const {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_number_integer()) fail_key(key, fmt::format("expected an integer, got {}", v.type_name()));
    // An unsigned value above INT64_MAX must not read as negative: compare it as unsigned.
    const bool inside = v.is_number_unsigned()
                            ? v.get<uint64_t>() <= static_cast<uint64_t>(std::max(hi, 0)) && static_cast<int64_t>(v.get<uint64_t>()) >= lo
                            : v.get<int64_t>() >= lo && v.get<int64_t>() <= hi;
    if (!inside) fail_key(key, fmt::format("{} outside {}..{}", json_number_text(v), lo, hi));
    return static_cast<int>(v.get<int64_t>());
  }
  std::string string(const std::string& key, const std::string& def) const {
    if (!has(key)) return def;
    const json& v = raw(key);
    if (!v.is_string()) fail_key(key, fmt::format("expected a string, got {}", v.type_name()));
    return v.get<std::string>();
  }
  // A fixed-length array of numbers.
  std::vector<double> numbers(const json& v, const std::string& path, size_t n_min, size_t n_max) const {
    if (!v.is_array() || v.size() < n_min || v.size() > n_max)
      throw InputError(where(path, n_min == n_max ? fmt::format("expected an array of {} numbers", n_min)
                                                  : fmt::format("expected an array of {}..{} numbers", n_min, n_max)));
    std::vector<double> out;
    for (const json& e : v) {
      if (!e.is_number() || !std::isfinite(e.get<double>()) || std::fabs(e.get<double>()) > kMaxSceneMagnitude)
        throw InputError(where(path, fmt::format("expected finite numbers within +-{:g}, found {}", kMaxSceneMagnitude,
                                                 json_number_text(e))));
      out.push_back(e.get<double>());
    }
    return out;
  }
  glm::dvec3 vec3(const std::string& key, glm::dvec3 def) const {
    if (!has(key)) return def;
    const auto v = numbers(raw(key), child(key), 3, 3);
    return {v[0], v[1], v[2]};
  }
  glm::dvec2 vec2(const std::string& key, glm::dvec2 def) const {
    if (!has(key)) return def;
    const auto v = numbers(raw(key), child(key), 2, 2);
    return {v[0], v[1]};
  }
  // An array of `n` arrays of `dim` numbers.
  std::vector<std::vector<double>> points(const std::string& key, size_t n, size_t dim) const {
    const json& v = raw(key);
    if (!v.is_array() || v.size() != n) fail_key(key, fmt::format("expected an array of {} points", n));
    std::vector<std::vector<double>> out;
    for (size_t i = 0; i < n; ++i) out.push_back(numbers(v[i], fmt::format("{}[{}]", child(key), i), dim, dim));
    return out;
  }
  void require(const std::string& key) const {
    if (!has(key)) fail(fmt::format("missing key '{}'", key));
  }

 private:
  const json& j_;
  std::string path_;
  const std::string& source_;
};

// ---- Transform: world = T R_z R_y R_x S p (rotations in degrees, right-handed) ----
struct Transform {
  glm::dvec3 translate{0.0}, rotate_deg{0.0}, scale{1.0};
  glm::dvec3 apply(glm::dvec3 p) const {
    p *= scale;
    const auto rot = [](double& a, double& b, double deg) {
      const double r = deg * std::numbers::pi / 180.0, c = std::cos(r), s = std::sin(r);
      const double a2 = c * a - s * b, b2 = s * a + c * b;
      a = a2;
      b = b2;
    };
    rot(p.y, p.z, rotate_deg.x);  // about x: y -> z
    rot(p.z, p.x, rotate_deg.y);  // about y: z -> x
    rot(p.x, p.y, rotate_deg.z);  // about z: x -> y
    return p + translate;
  }
};

Transform parse_transform(const Obj& mesh) {
  Transform tr;
  if (!mesh.has("transform")) return tr;
  const Obj o(mesh.raw("transform"), mesh.child("transform"), mesh.source(), {"translate", "rotate_deg", "scale"});
  tr.translate = o.vec3("translate", tr.translate);
  tr.rotate_deg = o.vec3("rotate_deg", tr.rotate_deg);
  if (o.has("scale") && o.raw("scale").is_number())
    tr.scale = glm::dvec3(o.number("scale", 1.0));
  else
    tr.scale = o.vec3("scale", tr.scale);
  return tr;
}

Camera parse_camera(const Obj& scene) {
  Camera cam;
  if (!scene.has("camera")) return cam;
  const Obj o(scene.raw("camera"), "camera", scene.source(), {"position", "look_at", "up", "fov_y", "near", "far"});
  cam.position = o.vec3("position", cam.position);
  cam.look_at = o.vec3("look_at", cam.look_at);
  cam.up = o.vec3("up", cam.up);
  cam.fov_y_deg = o.number("fov_y", cam.fov_y_deg);
  cam.near_plane = o.number("near", cam.near_plane);
  cam.far_plane = o.number("far", cam.far_plane);
  if (!(cam.fov_y_deg > 0.5 && cam.fov_y_deg < 179.5)) o.fail_key("fov_y", "must be in (0.5, 179.5) degrees");
  if (!(cam.near_plane > 0 && cam.far_plane > cam.near_plane)) o.fail_key("near", "need 0 < near < far");
  const glm::dvec3 dir = cam.look_at - cam.position;
  if (glm::length(dir) == 0.0) o.fail_key("look_at", "equals the camera position");
  if (glm::length(glm::cross(dir, cam.up)) < 1e-9 * glm::length(dir) * glm::length(cam.up))
    o.fail_key("up", "is parallel to the viewing direction");
  return cam;
}

std::array<double, 4> parse_background(const Obj& scene) {
  if (!scene.has("background")) return {0, 0, 0, 1};
  const auto v = scene.numbers(scene.raw("background"), "background", 3, 4);
  for (double c : v)
    if (c < 0 || c > 1) scene.fail_key("background", "components must be in [0, 1]");
  return {v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
}

// Textures are shared between stages that name the same source with the same keys.
using TextureCache = std::map<std::pair<std::string, Params>, LoadedTexture>;

// A JSON value as the text a parameter table parses: strings as they are, numbers and booleans as
// JSON writes them.
std::string value_text(const Obj& o, const std::string& key) {
  const json& v = o.raw(key);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number() || v.is_boolean()) return json_dump(v);
  o.fail_key(key, fmt::format("expected a string, number or boolean, got {}", v.type_name()));
}

void parse_texture(const Obj& stage, const std::string& base_dir, TextureCache& cache, TextureStage& out) {
  stage.require("texture");
  std::set<std::string> keys{"procedural", "size", "file"};
  for (const char* k : texture_param_keys()) keys.insert(k);
  const Obj o(stage.raw("texture"), stage.child("texture"), stage.source(), keys);
  if (o.has("procedural") == o.has("file")) o.fail("needs exactly one of 'procedural' or 'file'");
  if (o.has("file") && o.has("size")) o.fail_key("size", "only valid with 'procedural'");
  TextureSpec spec;
  if (o.has("procedural")) {
    spec.source = fmt::format("proc:{}:{}", o.string("procedural", ""), o.integer("size", 256, 1, 4096));
  } else {
    std::filesystem::path path(o.string("file", ""));
    if (path.is_relative() && !base_dir.empty()) path = std::filesystem::path(base_dir) / path;
    spec.source = path.string();
  }
  for (const char* k : texture_param_keys())
    if (o.has(k)) spec.params[k] = value_text(o, k);
  const auto key = std::pair{spec.source, spec.params};
  if (!cache.contains(key)) cache[key] = load_texture_spec(spec, o.location(o.child(o.has("file") ? "file" : "procedural")));
  out.spec = spec;
  out.texture = cache[key].texture;
  out.truth = cache[key].truth;
}

// A stage's sampler: the keys of the sampler table (bindings.hpp); scenes default to
// LINEAR_MIPMAP_LINEAR.
SamplerDescriptor parse_sampler(const Obj& stage) {
  SamplerDescriptor base;
  base.mode = FilterMode{BaseFilter::Linear, MipMode::Linear};
  if (!stage.has("sampler")) return base;
  std::set<std::string> keys;
  for (const SamplerParam& p : sampler_params()) keys.insert(p.key);
  const Obj o(stage.raw("sampler"), stage.child("sampler"), stage.source(), keys);
  for (const SamplerParam& p : sampler_params()) {
    if (!o.has(p.key)) continue;
    const std::string text = value_text(o, p.key);  // names the key itself when the value is no scalar
    try {
      set_sampler_param(base, p.key, text);
    } catch (const InputError& e) {
      o.fail_key(p.key, e.what());
    }
  }
  try {
    base.validate();
  } catch (const InputError& e) {
    o.fail(e.what());
  }
  return base;
}

TextureStage parse_stage(const Obj& o, const std::string& base_dir, TextureCache& cache, bool first) {
  TextureStage st;
  parse_texture(o, base_dir, cache, st);
  st.sampler = parse_sampler(o);
  st.uv_set = o.integer("uv_set", 0, 0, 1);
  st.combine.env = first ? TexEnv::Replace : TexEnv::Modulate;
  if (o.has("env")) {
    try {
      st.combine.env = tex_env_from_name(o.string("env", ""));
    } catch (const InputError& e) {
      o.fail_key("env", e.what());
    }
  }
  st.combine.rgb_scale = o.integer("rgb_scale", 1, 1, 4);
  if (st.combine.rgb_scale == 3) o.fail_key("rgb_scale", "must be 1, 2 or 4");
  return st;
}

std::vector<TextureStage> parse_material(const Obj& mesh, const std::string& base_dir, TextureCache& cache) {
  std::vector<TextureStage> stages;
  if (mesh.has("stages")) {
    if (mesh.has("texture") || mesh.has("sampler")) mesh.fail("give either 'stages' or 'texture' and 'sampler', not both");
    const json& list = mesh.raw("stages");
    if (!list.is_array() || list.empty() || list.size() > kMaxStages)
      mesh.fail_key("stages", fmt::format("expected an array of 1..{} stages", kMaxStages));
    for (size_t k = 0; k < list.size(); ++k) {
      const Obj o(list[k], fmt::format("{}[{}]", mesh.child("stages"), k), mesh.source(),
                  {"texture", "sampler", "uv_set", "env", "rgb_scale"});
      stages.push_back(parse_stage(o, base_dir, cache, k == 0));
    }
  } else {
    stages.push_back(parse_stage(mesh, base_dir, cache, true));
  }
  for (size_t k = 0; k < stages.size(); ++k)
    if (stages.size() > 1 && stages[k].texture->format == TexelFormat::VS16X2)
      mesh.fail_key("stages", fmt::format("stage {} is vs16x2: signed textures combine only as a single replace stage", k));
  return stages;
}

// Primitive-specific keys, in addition to the common ones.
const std::map<std::string, std::set<std::string>>& primitive_keys() {
  static const std::map<std::string, std::set<std::string>> keys{
      {"quad", {"corners", "uv"}},
      {"plane", {"size", "uv_repeat"}},
      {"cube", {}},
      {"sphere", {"segments"}},
      {"cylinder", {"segments", "uv_repeat"}},
      {"bezier_patch", {"control_points", "tessellation", "uv_repeat"}},
  };
  return keys;
}

// The primitive's mesh; with `unit` its UVs are the unit parametrization (no uv / uv_repeat keys).
Mesh build_primitive(const Obj& o, const std::string& primitive, bool unit) {
  if (primitive == "quad") {
    o.require("corners");
    const auto c = o.points("corners", 4, 3);
    std::array<glm::dvec3, 4> corners;
    for (size_t i = 0; i < 4; ++i) corners[i] = {c[i][0], c[i][1], c[i][2]};
    std::array<glm::dvec2, 4> uv{glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    if (o.has("uv") && !unit) {
      const auto u = o.points("uv", 4, 2);
      for (size_t i = 0; i < 4; ++i) uv[i] = {u[i][0], u[i][1]};
    }
    return make_quad_mesh(corners, uv);
  }
  const glm::dvec2 repeat = unit ? glm::dvec2{1, 1} : o.vec2("uv_repeat", {1, 1});
  if (primitive == "plane") return make_plane_mesh(o.vec2("size", {10, 10}), repeat);
  if (primitive == "cube") return make_cube_mesh();
  if (primitive == "sphere") {
    glm::dvec2 seg = o.vec2("segments", {48, 24});
    if (seg.x < 3 || seg.y < 2 || seg.x > 1024 || seg.y > 1024 || seg.x != std::floor(seg.x) || seg.y != std::floor(seg.y))
      o.fail_key("segments", "needs integers [lon >= 3, lat >= 2], at most 1024");
    return make_sphere_mesh(static_cast<int>(seg.x), static_cast<int>(seg.y));
  }
  if (primitive == "cylinder") {
    glm::dvec2 seg = o.vec2("segments", {64, 16});
    if (seg.x < 3 || seg.y < 1 || seg.x > 1024 || seg.y > 1024 || seg.x != std::floor(seg.x) || seg.y != std::floor(seg.y))
      o.fail_key("segments", "needs integers [around >= 3, along >= 1], at most 1024");
    return make_cylinder_mesh(static_cast<int>(seg.x), static_cast<int>(seg.y), repeat);
  }
  o.require("control_points");
  const auto c = o.points("control_points", 16, 3);
  std::array<glm::dvec3, 16> control;
  for (size_t i = 0; i < 16; ++i) control[i] = {c[i][0], c[i][1], c[i][2]};
  return make_bezier_patch_mesh(control, o.integer("tessellation", 32, 1, 256), repeat);
}

Mesh parse_mesh(const json& j, const std::string& path, const std::string& source, const std::string& base_dir,
                TextureCache& cache) {
  // First pass: the primitive decides which keys are allowed.
  std::string primitive;
  if (j.is_object() && j.contains("primitive") && j.at("primitive").is_string()) primitive = j.at("primitive");
  const auto& keys = primitive_keys();
  std::set<std::string> allowed{"primitive", "transform", "texture", "sampler", "stages", "uv_set", "env", "rgb_scale",
                                "uv1_repeat", "uv1_offset", "name"};
  if (keys.contains(primitive)) allowed.insert(keys.at(primitive).begin(), keys.at(primitive).end());
  const Obj o(j, path, source, allowed);
  o.require("primitive");
  primitive = o.string("primitive", "");
  if (!keys.contains(primitive))
    o.fail_key("primitive",
               fmt::format("unknown primitive '{}' (valid: quad, plane, cube, sphere, cylinder, bezier_patch)", primitive));
  o.string("name", "");
  if (o.has("stages"))
    for (const char* k : {"uv_set", "env", "rgb_scale"})
      if (o.has(k)) o.fail_key(k, "belongs to a stage of 'stages'");
  Mesh mesh = build_primitive(o, primitive, false);
  // UV set 1: the primitive's unit parametrization (its UVs with no repeat), scaled and offset.
  const Mesh unit = build_primitive(o, primitive, true);
  const glm::dvec2 rep1 = o.vec2("uv1_repeat", {1, 1}), off1 = o.vec2("uv1_offset", {0, 0});
  for (size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i].uv1 = unit.vertices[i].uv * rep1 + off1;
  mesh.primitive = primitive;
  const Transform tr = parse_transform(o);
  for (Vertex& v : mesh.vertices) v.pos = tr.apply(v.pos);
  mesh.stages = parse_material(o, base_dir, cache);
  return mesh;
}

json parse_json(const std::string& text, const std::string& source) {
  return parse_json_input(text, source);  // InputError "FILE: line L, column C: ..." (json_input.hpp)
}

}  // namespace

// ---- Mesh generators ----

Mesh make_quad_mesh(const std::array<glm::dvec3, 4>& corners, const std::array<glm::dvec2, 4>& uv) {
  Mesh m;
  for (size_t i = 0; i < 4; ++i) m.vertices.push_back({corners[i], uv[i]});
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

Mesh make_plane_mesh(glm::dvec2 size, glm::dvec2 uv_repeat) {
  const double hx = size.x / 2, hz = size.y / 2;
  return make_quad_mesh({glm::dvec3{-hx, 0, -hz}, {hx, 0, -hz}, {hx, 0, hz}, {-hx, 0, hz}},
                        {glm::dvec2{0, 0}, {uv_repeat.x, 0}, {uv_repeat.x, uv_repeat.y}, {0, uv_repeat.y}});
}

Mesh make_cube_mesh() {
  // Per face: outward normal n, and the directions of +s (right) and -t (up) on that face.
  struct Face {
    glm::dvec3 n, right, up;
  };
  static const Face faces[] = {
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
      {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
  };
  Mesh m;
  for (const Face& f : faces) {
    const auto base = static_cast<uint32_t>(m.vertices.size());
    for (const glm::dvec2 uv : {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}})
      m.vertices.push_back({0.5 * f.n + (uv.x - 0.5) * f.right + (0.5 - uv.y) * f.up, uv});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
  }
  return m;
}

Mesh make_sphere_mesh(int segments_lon, int segments_lat) {
  // s = longitude / 2 pi, t = colatitude / pi (t = 0 at the north pole, +y). The pole rows produce
  // zero-area triangles, which the rasterizer skips.
  Mesh m;
  for (int j = 0; j <= segments_lat; ++j)
    for (int i = 0; i <= segments_lon; ++i) {
      const double u = static_cast<double>(i) / segments_lon, v = static_cast<double>(j) / segments_lat;
      const double phi = 2 * std::numbers::pi * u, theta = std::numbers::pi * v;
      m.vertices.push_back({0.5 * glm::dvec3{std::sin(theta) * std::cos(phi), std::cos(theta),
                                             -std::sin(theta) * std::sin(phi)},
                            {u, v}});
    }
  const auto idx = [&](int i, int j) { return static_cast<uint32_t>(j * (segments_lon + 1) + i); };
  for (int j = 0; j < segments_lat; ++j)
    for (int i = 0; i < segments_lon; ++i) {
      m.triangles.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)});
      m.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)});
    }
  return m;
}

Mesh make_cylinder_mesh(int segments_around, int segments_along, glm::dvec2 uv_repeat) {
  Mesh m;
  for (int j = 0; j <= segments_along; ++j)
    for (int i = 0; i <= segments_around; ++i) {
      const double u = static_cast<double>(i) / segments_around, v = static_cast<double>(j) / segments_along;
      const double phi = 2 * std::numbers::pi * u;
      m.vertices.push_back({{0.5 * std::cos(phi), 0.5 * std::sin(phi), -v}, {u * uv_repeat.x, v * uv_repeat.y}});
    }
  const auto idx = [&](int i, int j) { return static_cast<uint32_t>(j * (segments_around + 1) + i); };
  for (int j = 0; j < segments_along; ++j)
    for (int i = 0; i < segments_around; ++i) {
      m.triangles.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)});
      m.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)});
    }
  return m;
}

Mesh make_bezier_patch_mesh(const std::array<glm::dvec3, 16>& control, int tessellation, glm::dvec2 uv_repeat) {
  // Cubic tensor-product Bezier patch: P(u, v) = sum_ij B_i(u) B_j(v) P_ji, control row j along v.
  const auto bernstein = [](double x) {
    const double y = 1 - x;
    return std::array<double, 4>{y * y * y, 3 * x * y * y, 3 * x * x * y, x * x * x};
  };
  Mesh m;
  const int n = tessellation;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      const auto bu = bernstein(u), bv = bernstein(v);
      glm::dvec3 p{0.0};
      for (size_t r = 0; r < 4; ++r)
        for (size_t c = 0; c < 4; ++c) p += bv[r] * bu[c] * control[r * 4 + c];
      m.vertices.push_back({p, {u * uv_repeat.x, v * uv_repeat.y}});
    }
  const auto idx = [&](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)});
      m.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)});
    }
  return m;
}

// ---- Scenes ----

Scene parse_scene(const std::string& json_text, const std::string& source, const std::string& base_dir) {
  const std::string label = quote_path(source);  // the file in messages
  const json j = parse_json(json_text, label);
  const Obj o(j, "", label,
              {"description", "width", "height", "camera", "background", "meshes", "cull", "display_shift"});
  Scene scene;
  scene.name = std::filesystem::path(source).stem().string();
  scene.description = o.string("description", "");
  scene.width = o.integer("width", scene.width, 1, kMaxRenderSize);
  scene.height = o.integer("height", scene.height, 1, kMaxRenderSize);
  scene.camera = parse_camera(o);
  scene.background = parse_background(o);
  if (o.has("cull")) {
    try {
      scene.cull = kCullWindingNames.from_name(o.string("cull", ""));
    } catch (const InputError& e) {
      o.fail_key("cull", e.what());
    }
  }
  scene.display_shift = o.integer("display_shift", 0, 0, kMaxDisplayShift);
  o.require("meshes");
  const json& meshes = o.raw("meshes");
  if (!meshes.is_array()) o.fail_key("meshes", fmt::format("expected an array, got {}", meshes.type_name()));
  TextureCache cache;
  for (size_t i = 0; i < meshes.size(); ++i)
    scene.meshes.push_back(parse_mesh(meshes[i], fmt::format("meshes[{}]", i), label, base_dir, cache));
  return scene;
}

const std::vector<std::string>& builtin_scene_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (size_t i = 0; i < detail::kEmbeddedSceneCount; ++i) v.emplace_back(detail::kEmbeddedScenes[i].name);
    return v;
  }();
  return names;
}

const std::string& builtin_scene_json(const std::string& name) {
  static const std::map<std::string, std::string> texts = [] {
    std::map<std::string, std::string> m;
    for (size_t i = 0; i < detail::kEmbeddedSceneCount; ++i)
      m.emplace(detail::kEmbeddedScenes[i].name, detail::kEmbeddedScenes[i].json);
    return m;
  }();
  const auto it = texts.find(name);
  if (it == texts.end())
    throw InputError(fmt::format("unknown built-in scene '{}' ({}valid: {})", quote_input(name),
                                 did_you_mean(name, builtin_scene_names()), fmt::join(builtin_scene_names(), ", ")));
  return it->second;
}

Scene load_scene(const std::string& name_or_path) {
  const auto& names = builtin_scene_names();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end())
    return parse_scene(builtin_scene_json(name_or_path), name_or_path + ".json");
  std::error_code ec;
  if (!std::filesystem::exists(name_or_path, ec) && !ec)
    throw InputError(fmt::format("scene '{}' is neither a built-in scene ({}{}) nor a readable file", quote_input(name_or_path),
                                 did_you_mean(name_or_path, names), fmt::join(names, ", ")));
  const std::string text = read_input_file(name_or_path, "scene " + quoted_path(name_or_path), kMaxTextInputBytes);
  return parse_scene(text, name_or_path, std::filesystem::path(name_or_path).parent_path().string());
}

}  // namespace tfu
