#include "cmodel/gl_replay.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "cmodel/api_limits.hpp"
#include "cmodel/block_formats.hpp"
#include "cmodel/error.hpp"
#include "cmodel/gl_trace.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu::gl {
namespace {

constexpr uint32_t kDepthMax = (1u << 24) - 1;  // 24-bit depth buffer
constexpr int kUnits = 2;                       // texture units executed

// ---- Texture objects ----
// The S3TC internal formats of GL_EXT_texture_compression_s3tc a glTexImage2D may ask for with
// uncompressed data: the driver compresses the level it is given into the format's blocks (the
// extension's "Modifications to Chapter 3": the image is stored in the compressed internal format).
// apitrace prints the enum's name; its number is the format's gl_internal_format (block_formats.hpp).
struct CompressedInternalFormat {
  const char* name;
  BlockFormat format;
};
constexpr std::array<CompressedInternalFormat, 4> kS3tcInternalFormats{{
    {"GL_COMPRESSED_RGB_S3TC_DXT1_EXT", BlockFormat::BC1},    // base format RGB: alpha reads 1.0
    {"GL_COMPRESSED_RGBA_S3TC_DXT1_EXT", BlockFormat::BC1A},  // alpha < 128: code 3, transparent black
    {"GL_COMPRESSED_RGBA_S3TC_DXT3_EXT", BlockFormat::BC2},
    {"GL_COMPRESSED_RGBA_S3TC_DXT5_EXT", BlockFormat::BC3},
}};

std::optional<BlockFormat> s3tc_internal_format(const std::string& internal) {
  for (const CompressedInternalFormat& f : kS3tcInternalFormats)
    if (internal == f.name || internal == std::to_string(block_format_info(f.format).gl_internal_format))
      return f.format;
  return std::nullopt;
}

const char* s3tc_name(BlockFormat f) {
  for (const CompressedInternalFormat& c : kS3tcInternalFormats)
    if (c.format == f) return c.name;
  return "?";
}

struct TextureObject {
  std::vector<Image> levels;  // by level; width 0: not specified. The texels as uploaded (RGBA8)
  // By level: the S3TC format the level is stored in (compressed when the texture is built), or
  // none (RGBA8). GL 1.5 Sec. 3.8.10: a texture whose levels differ in internal format is incomplete.
  std::vector<std::optional<BlockFormat>> compression;
  bool rgb_only = false;      // level 0's internal format has no alpha (RGB): alpha reads 1.0
  std::string min = "GL_NEAREST_MIPMAP_LINEAR", mag = "GL_LINEAR", wrap_s = "GL_REPEAT", wrap_t = "GL_REPEAT";
  double max_aniso = 1.0;
  std::shared_ptr<const Texture> built;  // the unit's texture of the current levels (made on first draw)
  bool mipmapped() const { return min != "GL_NEAREST" && min != "GL_LINEAR"; }
};

struct ArrayPointer {
  bool enabled = false;
  int size = 0;
  std::string type;
  int stride = 0;
  const Call* data = nullptr;  // the (fake) call whose blob holds the array from vertex 0
};

struct UnitState {
  uint32_t bound = 0;
  bool enabled = false;
  std::string env = "GL_MODULATE";
  ArrayPointer texcoord;
  glm::dvec2 current{0.0};
};

struct State {
  std::map<uint32_t, TextureObject> textures;
  std::array<UnitState, kUnits> units{};
  int active = 0, client_active = 0;
  ArrayPointer vertex, colour;
  glm::dvec4 current_colour{255.0};
  bool locked = false;
  int64_t lock_first = 0, lock_count = 0;
  std::string matrix_mode = "GL_MODELVIEW";
  std::vector<glm::dmat4> modelview{glm::dmat4(1.0)}, projection{glm::dmat4(1.0)};
  int vp_x = 0, vp_y = 0, vp_w = 0, vp_h = 0;
  int sc_x = 0, sc_y = 0, sc_w = 0, sc_h = 0;
  bool scissor = false;
  bool depth_test = false, depth_write = true;
  Compare depth_func = Compare::Less;
  double depth_near = 0, depth_far = 1;
  bool offset_fill = false;
  double offset_factor = 0, offset_units = 0;
  bool cull = false;
  std::string cull_mode = "GL_BACK";
  bool front_ccw = true;
  bool alpha_test = false;
  Compare alpha_func = Compare::Always;
  double alpha_ref = 0;
  bool blend = false;
  BlendFactor src = BlendFactor::One, dst = BlendFactor::Zero;
  glm::dvec4 clear_colour{0.0};
  double clear_depth = 1.0;
  std::map<std::string, uint64_t> unsupported_enabled;  // caps / client arrays enabled that no draw may use
};

const std::map<std::string, Compare>& compare_names() {
  static const std::map<std::string, Compare> m{{"GL_NEVER", Compare::Never},    {"GL_LESS", Compare::Less},
                                                {"GL_EQUAL", Compare::Equal},    {"GL_LEQUAL", Compare::LessEqual},
                                                {"GL_GREATER", Compare::Greater}, {"GL_NOTEQUAL", Compare::NotEqual},
                                                {"GL_GEQUAL", Compare::GreaterEqual}, {"GL_ALWAYS", Compare::Always}};
  return m;
}

const std::map<std::string, BlendFactor>& blend_names() {
  static const std::map<std::string, BlendFactor> m{
      {"GL_ZERO", BlendFactor::Zero},
      {"GL_ONE", BlendFactor::One},
      {"GL_SRC_COLOR", BlendFactor::SrcColour},
      {"GL_ONE_MINUS_SRC_COLOR", BlendFactor::OneMinusSrcColour},
      {"GL_DST_COLOR", BlendFactor::DstColour},
      {"GL_ONE_MINUS_DST_COLOR", BlendFactor::OneMinusDstColour},
      {"GL_SRC_ALPHA", BlendFactor::SrcAlpha},
      {"GL_ONE_MINUS_SRC_ALPHA", BlendFactor::OneMinusSrcAlpha},
      {"GL_DST_ALPHA", BlendFactor::DstAlpha},
      {"GL_ONE_MINUS_DST_ALPHA", BlendFactor::OneMinusDstAlpha},
      {"GL_SRC_ALPHA_SATURATE", BlendFactor::SrcAlphaSaturate}};
  return m;
}

bool compare(Compare f, uint32_t incoming, uint32_t stored) {
  switch (f) {
    case Compare::Never: return false;
    case Compare::Less: return incoming < stored;
    case Compare::Equal: return incoming == stored;
    case Compare::LessEqual: return incoming <= stored;
    case Compare::Greater: return incoming > stored;
    case Compare::NotEqual: return incoming != stored;
    case Compare::GreaterEqual: return incoming >= stored;
    case Compare::Always: return true;
  }
  return true;
}

// The blend factor of channel ch (0..2 colour, 3 alpha) on 8-bit codes (255 = 1.0).
uint32_t blend_factor(BlendFactor f, const Rgba8& s, const Rgba8& d, size_t ch) {
  const auto at = [ch](const Rgba8& c) -> uint32_t { return ch == 0 ? c.r : ch == 1 ? c.g : ch == 2 ? c.b : c.a; };
  switch (f) {
    case BlendFactor::Zero: return 0;
    case BlendFactor::One: return 255;
    case BlendFactor::SrcColour: return at(s);
    case BlendFactor::OneMinusSrcColour: return 255 - at(s);
    case BlendFactor::DstColour: return at(d);
    case BlendFactor::OneMinusDstColour: return 255 - at(d);
    case BlendFactor::SrcAlpha: return s.a;
    case BlendFactor::OneMinusSrcAlpha: return 255u - s.a;
    case BlendFactor::DstAlpha: return d.a;
    case BlendFactor::OneMinusDstAlpha: return 255u - d.a;
    case BlendFactor::SrcAlphaSaturate: return ch == 3 ? 255u : std::min<uint32_t>(s.a, 255u - d.a);
  }
  return 0;
}

// S sf + D df on 8-bit codes with one rounding: (x + 127) / 255 is round(x / 255) (255 is odd, so
// x / 255 is never a tie), clamped to 255.
Rgba8 blend(const Rgba8& s, const Rgba8& d, BlendFactor sf, BlendFactor df) {
  std::array<uint8_t, 4> out{};
  const std::array<uint32_t, 4> sv{s.r, s.g, s.b, s.a}, dv{d.r, d.g, d.b, d.a};
  for (size_t ch = 0; ch < 4; ++ch) {
    const uint32_t x = sv[ch] * blend_factor(sf, s, d, ch) + dv[ch] * blend_factor(df, s, d, ch);
    out[ch] = static_cast<uint8_t>(std::min<uint32_t>(255, (x + 127) / 255));
  }
  return {out[0], out[1], out[2], out[3]};
}

uint8_t unit_to_code(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }
uint32_t depth_code(double z) { return static_cast<uint32_t>(std::llround(std::clamp(z, 0.0, 1.0) * kDepthMax)); }

// The renderer's fragment operations on one quad, after the unit: `texels` holds 4 outputs per
// stage (stage-major).
void apply_quad(const DrawOps& d, const FragmentQuad& q, const Rgba8* texels, bool dst_alpha, Image& colour,
                std::vector<uint32_t>& depth) {
  for (size_t k = 0; k < 4; ++k) {
    if (!(q.mask >> k & 1u)) continue;
    Rgba8 c = q.primary[k];
    for (size_t st = 0; st < d.stages.size(); ++st) {
      Rgba8 next = combine_stage(c, texels[st * 4 + k], d.stages[st].combine);
      if (d.stages[st].keep_fragment_alpha) next.a = c.a;
      c = next;
    }
    if (d.alpha_test && !compare(d.alpha_func, c.a, d.alpha_ref)) continue;
    const int x = q.x + static_cast<int>(k & 1), y = q.y + static_cast<int>(k >> 1);
    const size_t idx = static_cast<size_t>(y) * static_cast<size_t>(colour.width) + static_cast<size_t>(x);
    if (d.depth_test && d.depth_write) depth[idx] = q.depth[k];
    Rgba8 out = c;
    if (d.blend) {
      Rgba8 dst = colour.texels[idx];
      if (!dst_alpha) dst.a = 255;
      out = blend(c, dst, d.src, d.dst);
    }
    if (!dst_alpha) out.a = 255;
    colour.texels[idx] = out;
  }
}

void apply_clear(const ClearOp& c, Image& colour, std::vector<uint32_t>& depth) {
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) {
      const size_t idx = static_cast<size_t>(y) * static_cast<size_t>(colour.width) + static_cast<size_t>(x);
      if (c.colour) colour.texels[idx] = c.colour_value;
      if (c.depth) depth[idx] = c.depth_value;
    }
}

// One vertex as fetched: object position, texture coordinates of both units, colour 0..255.
struct Vertex {
  glm::dvec4 pos{0, 0, 0, 1};
  std::array<glm::dvec2, 2> uv{};
  glm::dvec4 colour{255.0};
};

struct DrawTriangle {
  RasterTriangle tri;
  double offset = 0;  // polygon offset added to every window depth of the triangle
};

struct PendingDraw {
  std::vector<DrawTriangle> triangles;
  std::array<int, 4> rect{};  // pixel rectangle x0, y0, x1, y1 (viewport ∩ scissor ∩ framebuffer)
  std::vector<StageBinding> stages;
  std::vector<std::pair<int, int>> extents;  // level-0 size per stage
  std::vector<bool> anisotropic;             // per stage
  std::vector<int> uv_units;                 // per stage: the texture unit (its coordinates)
};

class Replayer {
 public:
  Replayer(const Dump& dump, int frame, const ReplayOptions& opts)
      : dump_(dump),
        builder_(opts.line_bytes),
        alpha_bits_(opts.alpha_bits),
        filter_override_(opts.min_filter),
        aniso_override_(opts.max_aniso) {
    if (alpha_bits_ != -1 && alpha_bits_ != 0 && alpha_bits_ != 8)
      throw InputError(fmt::format("alpha bits {}: expected 0 or 8 (or -1: the trace's visual)", alpha_bits_));
    out_.trace = dump.stream().trace;
    out_.frame = frame;
  }

  Replay run();

 private:
  const Dump& dump_;
  FrameBuilder builder_;
  int alpha_bits_;
  std::string filter_override_;         // ReplayOptions::min_filter
  int aniso_override_;                  // ReplayOptions::max_aniso
  int locked_pass_ = 0;                 // draws since the last glLockArraysEXT
  std::vector<glm::dmat4> modelviews_;  // the frame's distinct modelview matrices, by first use
  Replay out_;
  State st_;
  std::string context_;
  bool in_frame_ = false;
  std::vector<std::string> unsupported_;
  std::set<std::string> unsupported_names_;
  std::vector<PendingDraw> pending_;
  // glBegin / glEnd
  bool in_begin_ = false;
  std::string begin_mode_;
  std::vector<Vertex> immediate_;

  std::string where(const Call& c) const {
    return fmt::format("--gl-trace '{}': call {} {}", quote_path(out_.trace), c.number, c.name);
  }
  void unsupported(const std::string& name, const Call& c) {
    if (unsupported_names_.insert(name).second) unsupported_.push_back(fmt::format("{} (call {})", name, c.number));
  }
  static const std::string& text(const Call& c, const std::string& arg) {
    for (const auto& [n, v] : c.args)
      if (n == arg) return v.text;
    throw InputError(fmt::format("call {} {}: no argument {}", c.number, c.name, arg));
  }
  int int_arg(const Call& c, const std::string& arg, int lo, int hi) const {
    const double v = c.number_arg(arg);
    if (!(v >= lo && v <= hi) || v != std::floor(v))
      throw InputError(fmt::format("{}: {} = {} outside {}..{}", where(c), arg, v, lo, hi));
    return static_cast<int>(v);
  }
  glm::dmat4& current_matrix() { return st_.matrix_mode == "GL_PROJECTION" ? st_.projection.back() : st_.modelview.back(); }
  std::vector<glm::dmat4>& current_stack() { return st_.matrix_mode == "GL_PROJECTION" ? st_.projection : st_.modelview; }

  void execute(const Call& c);
  void enable(const Call& c, bool on);
  void client_state(const Call& c, bool on);
  void tex_image(const Call& c);
  void tex_sub_image(const Call& c);
  void tex_parameter(const Call& c);
  void set_pointer(const Call& c, ArrayPointer& p, std::initializer_list<int> sizes, std::initializer_list<const char*> types);
  void draw_elements(const Call& c);
  void draw_arrays(const Call& c);
  void end_immediate(const Call& c);
  void clear(const Call& c);
  // A draw of the frame under a state the replay does not execute (a cap or client array enabled).
  void check_enabled(const Call& c) {
    for (const auto& [name, call] : st_.unsupported_enabled) unsupported(name, c);
  }
  void submit(const Call& c, const std::string& mode, const std::vector<Vertex>& verts, const std::vector<uint32_t>& order);
  void override_sampler(SamplerDescriptor& sd) const;
  DrawFacts draw_facts(uint64_t triangles);
  std::vector<Vertex> fetch(const Call& c, const std::vector<uint32_t>& indices);
  std::array<int, 4> pixel_rect() const;
  void rasterize(const GoldenUnit& golden);
};

std::array<int, 4> Replayer::pixel_rect() const {
  const int W = out_.width, H = out_.height;
  // GL window rectangles (y up) as screen rows (y down).
  int x0 = std::max(0, st_.vp_x), x1 = std::min(W, st_.vp_x + st_.vp_w);
  int y0 = std::max(0, H - (st_.vp_y + st_.vp_h)), y1 = std::min(H, H - st_.vp_y);
  if (st_.scissor) {
    x0 = std::max(x0, st_.sc_x), x1 = std::min(x1, st_.sc_x + st_.sc_w);
    y0 = std::max(y0, H - (st_.sc_y + st_.sc_h)), y1 = std::min(y1, H - st_.sc_y);
  }
  return {x0, y0, std::max(x0, x1), std::max(y0, y1)};
}

void Replayer::enable(const Call& c, bool on) {
  const std::string& cap = text(c, "cap");
  if (cap == "GL_TEXTURE_2D") st_.units[static_cast<size_t>(st_.active)].enabled = on;
  else if (cap == "GL_BLEND") st_.blend = on;
  else if (cap == "GL_DEPTH_TEST") st_.depth_test = on;
  else if (cap == "GL_CULL_FACE") st_.cull = on;
  else if (cap == "GL_ALPHA_TEST") st_.alpha_test = on;
  else if (cap == "GL_POLYGON_OFFSET_FILL") st_.offset_fill = on;
  else if (cap == "GL_SCISSOR_TEST") st_.scissor = on;
  else if (cap == "GL_DITHER") {  // no effect at 8 bits per channel
  } else if (on) st_.unsupported_enabled[fmt::format("glEnable({})", cap)] = c.number;
  else st_.unsupported_enabled.erase(fmt::format("glEnable({})", cap));
}

void Replayer::client_state(const Call& c, bool on) {
  const std::string& a = text(c, "array");
  if (a == "GL_VERTEX_ARRAY") st_.vertex.enabled = on;
  else if (a == "GL_COLOR_ARRAY") st_.colour.enabled = on;
  else if (a == "GL_TEXTURE_COORD_ARRAY") st_.units[static_cast<size_t>(st_.client_active)].texcoord.enabled = on;
  else if (on) st_.unsupported_enabled[fmt::format("glEnableClientState({})", a)] = c.number;
  else st_.unsupported_enabled.erase(fmt::format("glEnableClientState({})", a));
}

void Replayer::tex_image(const Call& c) {
  const std::string& target = text(c, "target");
  if (target != "GL_TEXTURE_2D") return unsupported(fmt::format("glTexImage2D({})", target), c);
  const std::string& internal = text(c, "internalformat");
  const std::string& format = text(c, "format");
  const std::string& type = text(c, "type");
  const std::optional<BlockFormat> s3tc = s3tc_internal_format(internal);
  const bool rgb = internal == "GL_RGB" || internal == "GL_RGB8" || internal == "3" || s3tc == BlockFormat::BC1;
  const bool rgba =
      internal == "GL_RGBA" || internal == "GL_RGBA8" || internal == "4" || (s3tc && s3tc != BlockFormat::BC1);
  if (!rgb && !rgba) return unsupported(fmt::format("glTexImage2D internalformat {}", internal), c);
  if (format != "GL_RGBA" || type != "GL_UNSIGNED_BYTE")
    return unsupported(fmt::format("glTexImage2D format {} type {}", format, type), c);
  if (c.number_arg("border") != 0) return unsupported("glTexImage2D border", c);
  const int level = int_arg(c, "level", 0, kMaxLevels - 1);
  const int w = int_arg(c, "width", 1, kMaxTextureSize), h = int_arg(c, "height", 1, kMaxTextureSize);
  const std::vector<uint8_t> bytes = dump_.blob(c, "pixels", uint64_t{4} * static_cast<uint64_t>(w) * static_cast<uint64_t>(h));
  TextureObject& t = st_.textures[st_.units[static_cast<size_t>(st_.active)].bound];
  if (t.levels.size() <= static_cast<size_t>(level)) {
    t.levels.resize(static_cast<size_t>(level) + 1);
    t.compression.resize(static_cast<size_t>(level) + 1);
  }
  t.compression[static_cast<size_t>(level)] = s3tc;
  Image im(w, h);
  for (size_t i = 0; i < im.texels.size(); ++i)
    im.texels[i] = {bytes[4 * i], bytes[4 * i + 1], bytes[4 * i + 2], rgb ? uint8_t{255} : bytes[4 * i + 3]};
  t.levels[static_cast<size_t>(level)] = std::move(im);
  if (level == 0) t.rgb_only = rgb;
  t.built.reset();
}

// A rectangle of a specified level replaced (GL 1.5 Sec. 3.8.2); the texture's descriptor is made anew.
void Replayer::tex_sub_image(const Call& c) {
  const std::string& target = text(c, "target");
  if (target != "GL_TEXTURE_2D") return unsupported(fmt::format("glTexSubImage2D({})", target), c);
  if (text(c, "format") != "GL_RGBA" || text(c, "type") != "GL_UNSIGNED_BYTE")
    return unsupported(fmt::format("glTexSubImage2D format {} type {}", text(c, "format"), text(c, "type")), c);
  const int level = int_arg(c, "level", 0, kMaxLevels - 1);
  TextureObject& t = st_.textures[st_.units[static_cast<size_t>(st_.active)].bound];
  if (t.levels.size() <= static_cast<size_t>(level) || t.levels[static_cast<size_t>(level)].empty())
    throw InputError(fmt::format("{}: level {} of texture {} was never specified", where(c), level,
                                 st_.units[static_cast<size_t>(st_.active)].bound));
  Image& im = t.levels[static_cast<size_t>(level)];
  const int x0 = int_arg(c, "xoffset", 0, im.width), y0 = int_arg(c, "yoffset", 0, im.height);
  const int w = int_arg(c, "width", 0, im.width - x0), h = int_arg(c, "height", 0, im.height - y0);
  // GL_EXT_texture_compression_s3tc: a sub-image of an S3TC level must cover whole 4x4 blocks (offsets
  // multiples of 4; width and height multiples of 4 or reaching the level's edge), else
  // INVALID_OPERATION. On whole blocks, compressing the updated level anew gives the blocks the driver
  // writes: every block is encoded from its own 16 texels alone.
  if (const std::optional<BlockFormat> f = t.compression[static_cast<size_t>(level)];
      f && (x0 % 4 != 0 || y0 % 4 != 0 || (w % 4 != 0 && x0 + w != im.width) || (h % 4 != 0 && y0 + h != im.height)))
    throw InputError(
        fmt::format("{}: the rectangle {}x{} at ({}, {}) of level {} ({}x{}, {}) is not made of whole 4x4 blocks "
                    "(GL_INVALID_OPERATION)",
                    where(c), w, h, x0, y0, level, im.width, im.height, s3tc_name(*f)));
  const std::vector<uint8_t> bytes = dump_.blob(c, "pixels", uint64_t{4} * static_cast<uint64_t>(w) * static_cast<uint64_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = 4 * (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x));
      im.at(x0 + x, y0 + y) = {bytes[i], bytes[i + 1], bytes[i + 2], t.rgb_only ? uint8_t{255} : bytes[i + 3]};
    }
  t.built.reset();
}

void Replayer::tex_parameter(const Call& c) {
  if (text(c, "target") != "GL_TEXTURE_2D") return unsupported(fmt::format("{}({})", c.name, text(c, "target")), c);
  TextureObject& t = st_.textures[st_.units[static_cast<size_t>(st_.active)].bound];
  const std::string& pname = text(c, "pname");
  const std::string& param = text(c, "param");
  const bool was_mipmapped = t.mipmapped();
  static const std::set<std::string> min_filters{"GL_NEAREST", "GL_LINEAR", "GL_NEAREST_MIPMAP_NEAREST", "GL_LINEAR_MIPMAP_NEAREST",
                                                 "GL_NEAREST_MIPMAP_LINEAR", "GL_LINEAR_MIPMAP_LINEAR"};
  static const std::set<std::string> wraps{"GL_REPEAT", "GL_CLAMP_TO_EDGE", "GL_MIRRORED_REPEAT", "GL_CLAMP_TO_BORDER"};
  if (pname == "GL_TEXTURE_MIN_FILTER" && min_filters.contains(param)) t.min = param;
  else if (pname == "GL_TEXTURE_MAG_FILTER" && (param == "GL_NEAREST" || param == "GL_LINEAR")) t.mag = param;
  else if (pname == "GL_TEXTURE_WRAP_S" && wraps.contains(param)) t.wrap_s = param;
  else if (pname == "GL_TEXTURE_WRAP_T" && wraps.contains(param)) t.wrap_t = param;
  else if (pname == "GL_TEXTURE_MAX_ANISOTROPY_EXT" || pname == "GL_TEXTURE_MAX_ANISOTROPY") {
    const double v = c.number_arg("param");
    if (!(v >= 1.0)) throw InputError(fmt::format("{}: anisotropy {} below 1", where(c), v));
    t.max_aniso = v;
  } else return unsupported(fmt::format("{}({} {})", c.name, pname, param), c);
  // The parameters are the sampler's; only the levels the texture holds (all, or level 0 alone) are the texture's.
  if (t.mipmapped() != was_mipmapped) t.built.reset();
}

void Replayer::set_pointer(const Call& c, ArrayPointer& p, std::initializer_list<int> sizes,
                           std::initializer_list<const char*> types) {
  const int size = int_arg(c, "size", 1, 4);
  const std::string& type = text(c, "type");
  if (std::find(sizes.begin(), sizes.end(), size) == sizes.end() ||
      std::find_if(types.begin(), types.end(), [&](const char* t) { return type == t; }) == types.end())
    return unsupported(fmt::format("{}(size {}, {})", c.name, size, type), c);
  p.size = size;
  p.type = type;
  p.stride = int_arg(c, "stride", 0, 1 << 16);
  // A user pointer carries its data in a blob only in apitrace's fake calls before each draw.
  p.data = nullptr;
  for (const auto& [name, v] : c.args)
    if (name == "pointer" && v.kind == Value::Kind::Blob) p.data = &c;
}

// The vertices `indices` name, fetched from the enabled arrays (else the current values).
std::vector<Vertex> Replayer::fetch(const Call& c, const std::vector<uint32_t>& indices) {
  uint32_t max_index = 0;
  for (uint32_t i : indices) max_index = std::max(max_index, i);
  const auto load = [&](const ArrayPointer& p, const char* what) -> std::pair<std::vector<uint8_t>, int> {
    if (p.data == nullptr) throw InputError(fmt::format("{}: the {} array has no data in the trace", where(c), what));
    const int elem = p.type == "GL_UNSIGNED_BYTE" ? 1 : 4;
    const int stride = p.stride ? p.stride : p.size * elem;
    const uint64_t need = uint64_t{max_index} * static_cast<uint64_t>(stride) + static_cast<uint64_t>(p.size * elem);
    return {dump_.blob(*p.data, "pointer", need), stride};
  };
  const auto read_float = [](const std::vector<uint8_t>& b, size_t off) {
    float f = 0;
    std::memcpy(&f, b.data() + off, sizeof f);
    return static_cast<double>(f);
  };
  std::vector<Vertex> v(indices.size());
  if (!st_.vertex.enabled) throw InputError(fmt::format("{}: a draw without GL_VERTEX_ARRAY enabled", where(c)));
  const auto [pos, pstride] = load(st_.vertex, "vertex");
  for (size_t i = 0; i < indices.size(); ++i) {
    const size_t base = size_t{indices[i]} * static_cast<size_t>(pstride);
    for (int k = 0; k < st_.vertex.size; ++k) v[i].pos[k] = read_float(pos, base + 4 * static_cast<size_t>(k));
    if (st_.vertex.size < 3) v[i].pos.z = 0;
    if (st_.vertex.size < 4) v[i].pos.w = 1;
  }
  for (int u = 0; u < kUnits; ++u) {
    const UnitState& us = st_.units[static_cast<size_t>(u)];
    if (!us.texcoord.enabled) {
      for (Vertex& x : v) x.uv[static_cast<size_t>(u)] = us.current;
      continue;
    }
    const auto [tc, tstride] = load(us.texcoord, "texture coordinate");
    for (size_t i = 0; i < indices.size(); ++i) {
      const size_t base = size_t{indices[i]} * static_cast<size_t>(tstride);
      v[i].uv[static_cast<size_t>(u)] = {read_float(tc, base), read_float(tc, base + 4)};
    }
  }
  if (st_.colour.enabled) {
    const auto [col, cstride] = load(st_.colour, "colour");
    for (size_t i = 0; i < indices.size(); ++i) {
      const size_t base = size_t{indices[i]} * static_cast<size_t>(cstride);
      glm::dvec4 cv{255.0};
      for (int k = 0; k < st_.colour.size; ++k)
        cv[k] = st_.colour.type == "GL_UNSIGNED_BYTE" ? col[base + static_cast<size_t>(k)]
                                                     : std::clamp(read_float(col, base + 4 * static_cast<size_t>(k)), 0.0, 1.0) * 255.0;
      v[i].colour = cv;
    }
  } else {
    for (Vertex& x : v) x.colour = st_.current_colour;
  }
  return v;
}

// Triangles of a primitive mode as vertex positions in `verts` (GL 1.5 Sec. 2.6.1; quads and
// polygons as fans from their first vertex).
std::vector<uint32_t> triangle_order(const std::string& mode, size_t n, bool& ok) {
  std::vector<uint32_t> o;
  ok = true;
  const auto push = [&](size_t a, size_t b, size_t c) {
    o.push_back(static_cast<uint32_t>(a)), o.push_back(static_cast<uint32_t>(b)), o.push_back(static_cast<uint32_t>(c));
  };
  if (mode == "GL_TRIANGLES") {
    for (size_t i = 0; i + 2 < n; i += 3) push(i, i + 1, i + 2);
  } else if (mode == "GL_TRIANGLE_STRIP") {
    for (size_t i = 0; i + 2 < n; ++i) i % 2 ? push(i + 1, i, i + 2) : push(i, i + 1, i + 2);
  } else if (mode == "GL_TRIANGLE_FAN" || mode == "GL_POLYGON") {
    for (size_t i = 1; i + 1 < n; ++i) push(0, i, i + 1);
  } else if (mode == "GL_QUADS") {
    for (size_t i = 0; i + 3 < n; i += 4) push(i, i + 1, i + 2), push(i, i + 2, i + 3);
  } else if (mode == "GL_QUAD_STRIP") {
    for (size_t i = 0; i + 3 < n; i += 2) push(i, i + 1, i + 3), push(i, i + 3, i + 2);
  } else {
    ok = false;
  }
  return o;
}

void Replayer::draw_elements(const Call& c) {
  check_enabled(c);
  const std::string& type = text(c, "type");
  const int count = int_arg(c, "count", 0, 1 << 26);
  const int bytes = type == "GL_UNSIGNED_INT" ? 4 : type == "GL_UNSIGNED_SHORT" ? 2 : type == "GL_UNSIGNED_BYTE" ? 1 : 0;
  if (bytes == 0) return unsupported(fmt::format("glDrawElements type {}", type), c);
  const std::vector<uint8_t> raw = dump_.blob(c, "indices", static_cast<uint64_t>(count) * static_cast<uint64_t>(bytes));
  std::vector<uint32_t> indices(static_cast<size_t>(count));
  for (size_t i = 0; i < indices.size(); ++i) {
    uint32_t v = 0;
    std::memcpy(&v, raw.data() + i * static_cast<size_t>(bytes), static_cast<size_t>(bytes));
    indices[i] = v;
  }
  if (st_.locked) {
    ++out_.stats.locked_draws;
    for (uint32_t i : indices)
      if (static_cast<int64_t>(i) < st_.lock_first || static_cast<int64_t>(i) >= st_.lock_first + st_.lock_count)
        return unsupported("glDrawElements index outside the glLockArraysEXT range", c);
  }
  bool ok = true;
  const std::vector<uint32_t> order = triangle_order(text(c, "mode"), indices.size(), ok);
  if (!ok) return unsupported(fmt::format("glDrawElements({})", text(c, "mode")), c);
  std::vector<uint32_t> used(order.size());
  for (size_t i = 0; i < order.size(); ++i) used[i] = indices[order[i]];
  const std::vector<Vertex> verts = fetch(c, used);
  std::vector<uint32_t> seq(verts.size());
  for (size_t i = 0; i < seq.size(); ++i) seq[i] = static_cast<uint32_t>(i);
  submit(c, text(c, "mode"), verts, seq);
}

void Replayer::draw_arrays(const Call& c) {
  check_enabled(c);
  const int first = int_arg(c, "first", 0, 1 << 26), count = int_arg(c, "count", 0, 1 << 26);
  bool ok = true;
  const std::vector<uint32_t> order = triangle_order(text(c, "mode"), static_cast<size_t>(count), ok);
  if (!ok) return unsupported(fmt::format("glDrawArrays({})", text(c, "mode")), c);
  std::vector<uint32_t> used(order.size());
  for (size_t i = 0; i < order.size(); ++i) used[i] = static_cast<uint32_t>(first) + order[i];
  if (st_.locked) ++out_.stats.locked_draws;
  const std::vector<Vertex> verts = fetch(c, used);
  std::vector<uint32_t> seq(verts.size());
  for (size_t i = 0; i < seq.size(); ++i) seq[i] = static_cast<uint32_t>(i);
  submit(c, text(c, "mode"), verts, seq);
}

void Replayer::end_immediate(const Call& c) {
  in_begin_ = false;
  if (in_frame_) check_enabled(c);
  bool ok = true;
  const std::vector<uint32_t> order = triangle_order(begin_mode_, immediate_.size(), ok);
  if (!ok) return unsupported(fmt::format("glBegin({})", begin_mode_), c);
  if (in_frame_) submit(c, begin_mode_, immediate_, order);
  immediate_.clear();
}

void Replayer::clear(const Call& c) {
  const std::string& mask = text(c, "mask");
  ClearOp op;
  op.before_draw = static_cast<uint32_t>(pending_.size());
  op.colour = mask.find("GL_COLOR_BUFFER_BIT") != std::string::npos;
  op.depth = mask.find("GL_DEPTH_BUFFER_BIT") != std::string::npos;
  if (mask.find("GL_STENCIL_BUFFER_BIT") != std::string::npos || mask.find("GL_ACCUM_BUFFER_BIT") != std::string::npos)
    return unsupported("glClear of the stencil or accumulation buffer", c);
  const int W = out_.width, H = out_.height;
  op.x0 = 0, op.y0 = 0, op.x1 = W, op.y1 = H;
  if (st_.scissor) {
    op.x0 = std::clamp(st_.sc_x, 0, W), op.x1 = std::clamp(st_.sc_x + st_.sc_w, op.x0, W);
    op.y0 = std::clamp(H - (st_.sc_y + st_.sc_h), 0, H), op.y1 = std::clamp(H - st_.sc_y, op.y0, H);
  }
  op.colour_value = {unit_to_code(st_.clear_colour.r), unit_to_code(st_.clear_colour.g), unit_to_code(st_.clear_colour.b),
                     unit_to_code(st_.clear_colour.a)};
  op.depth_value = depth_code(st_.clear_depth);
  if (!st_.depth_write) op.depth = false;  // the depth mask applies to clears
  out_.clears.push_back(op);
}

// A draw of the frame: the state it runs under checked, its textures registered with the unit's
// frame, its triangles transformed, clipped, projected, snapped and culled.
void Replayer::submit(const Call& c, const std::string& mode, const std::vector<Vertex>& verts, const std::vector<uint32_t>& order) {
  (void)mode;
  ++out_.stats.draws;
  DrawOps ops;
  ops.call = c.number;
  ops.alpha_test = st_.alpha_test;
  ops.alpha_func = st_.alpha_func;
  ops.alpha_ref = unit_to_code(st_.alpha_ref);
  ops.depth_test = st_.depth_test;
  ops.depth_func = st_.depth_func;
  ops.depth_write = st_.depth_write;
  ops.blend = st_.blend;
  ops.src = st_.src;
  ops.dst = st_.dst;
  PendingDraw pd;
  for (int u = 0; u < kUnits; ++u) {
    const UnitState& us = st_.units[static_cast<size_t>(u)];
    if (!us.enabled) continue;
    static const std::map<std::string, TexEnv> envs{
        {"GL_MODULATE", TexEnv::Modulate}, {"GL_REPLACE", TexEnv::Replace}, {"GL_ADD", TexEnv::Add}, {"GL_DECAL", TexEnv::Decal}};
    const auto env = envs.find(us.env);
    if (env == envs.end()) {
      unsupported(fmt::format("GL_TEXTURE_ENV_MODE {}", us.env), c);
      continue;
    }
    auto it = st_.textures.find(us.bound);
    if (it == st_.textures.end() || it->second.levels.empty() || it->second.levels[0].empty()) {
      unsupported(fmt::format("texture {} sampled without level 0", us.bound), c);
      continue;
    }
    TextureObject& t = it->second;
    if (!t.built) {
      auto tex = std::make_shared<Texture>();
      tex->format = TexelFormat::RGBA8;
      tex->layout = MemoryLayout::Tiled;
      tex->levels.push_back(t.levels[0]);
      if (t.mipmapped()) {
        for (size_t l = 1; l < t.levels.size() && (tex->levels.back().width > 1 || tex->levels.back().height > 1); ++l) {
          const Image& im = t.levels[l];
          if (im.width != std::max(1, tex->levels.back().width / 2) || im.height != std::max(1, tex->levels.back().height / 2)) break;
          tex->levels.push_back(im);
        }
        if (tex->levels.back().width > 1 || tex->levels.back().height > 1) {
          unsupported(fmt::format("incomplete mipmapped texture {}", us.bound), c);
          continue;
        }
      }
      tex->validate(fmt::format("{}: texture {}", where(c), us.bound));
      // An S3TC texture: every level it uses stored in level 0's format, each compressed as the
      // driver does at upload (upload_compression.hpp: libsquish, range fit, per level).
      const std::optional<BlockFormat> f = t.compression[0];
      if (!std::all_of(t.compression.begin(), t.compression.begin() + static_cast<std::ptrdiff_t>(tex->levels.size()),
                       [&](const std::optional<BlockFormat>& g) { return g == f; })) {
        unsupported(fmt::format("texture {} with levels of different internal formats (incomplete)", us.bound), c);
        continue;
      }
      t.built = f ? std::make_shared<const Texture>(compress_texture(*tex, *f, fmt::format("gl-texture-{}", us.bound)))
                  : std::shared_ptr<const Texture>(std::move(tex));
    }
    const auto base = [](const std::string& f) { return f.rfind("GL_NEAREST", 0) == 0 ? BaseFilter::Nearest : BaseFilter::Linear; };
    SamplerDescriptor sd;
    sd.mode.base = base(t.min);
    sd.mode.mip = !t.mipmapped() ? MipMode::None : t.min.ends_with("MIPMAP_NEAREST") ? MipMode::Nearest : MipMode::Linear;
    if (base(t.mag) != sd.mode.base) {
      unsupported(fmt::format("GL_TEXTURE_MAG_FILTER {} with GL_TEXTURE_MIN_FILTER {}", t.mag, t.min), c);
      continue;
    }
    static const std::map<std::string, WrapMode> wraps{{"GL_REPEAT", WrapMode::Repeat},
                                                       {"GL_CLAMP_TO_EDGE", WrapMode::ClampToEdge},
                                                       {"GL_MIRRORED_REPEAT", WrapMode::MirroredRepeat},
                                                       {"GL_CLAMP_TO_BORDER", WrapMode::ClampToBorder}};
    sd.wrap_s = wraps.at(t.wrap_s);
    sd.wrap_t = wraps.at(t.wrap_t);
    // GL_TEXTURE_MAX_ANISOTROPY: the unit's probe limit is an integer, 1..16 (the value rounded down).
    sd.max_aniso = static_cast<int>(std::clamp(std::floor(t.max_aniso), 1.0, 16.0));
    if (t.mipmapped()) override_sampler(sd);
    const int ti = builder_.add_texture(t.built, TextureSpec{fmt::format("gl-texture-{}", us.bound), {}});
    const int si = builder_.add_sampler(sd);
    pd.stages.push_back({builder_.bind(ti, si), si});
    pd.extents.emplace_back(t.built->width(), t.built->height());
    pd.anisotropic.push_back(sd.anisotropic());
    pd.uv_units.push_back(u);
    StageEnv se;
    se.combine.env = env->second;
    se.keep_fragment_alpha = env->second == TexEnv::Replace && t.rgb_only;
    ops.stages.push_back(se);
  }
  // Triangles: object -> clip space, clipped, to the viewport and depth range, snapped, culled.
  const glm::dmat4 mvp = st_.projection.back() * st_.modelview.back();
  const int W = out_.width, H = out_.height;
  pd.rect = pixel_rect();
  const auto to_window = [&](const ClipVertex& cv) {
    const double inv_w = 1.0 / cv.p.w;
    ScreenVertex v;
    v.x = st_.vp_x + (cv.p.x * inv_w + 1.0) * 0.5 * st_.vp_w;
    v.y = H - (st_.vp_y + (cv.p.y * inv_w + 1.0) * 0.5 * st_.vp_h);
    v.z = st_.depth_near + (st_.depth_far - st_.depth_near) * (cv.p.z * inv_w + 1.0) * 0.5;
    v.inv_w = inv_w;
    for (size_t k = 0; k < 2; ++k) v.uv_w[k] = cv.uv[k] * inv_w;
    v.colour_w = cv.colour * inv_w;
    return v;
  };
  for (size_t i = 0; i + 2 < order.size(); i += 3) {
    ++out_.stats.triangles;
    Polygon poly;
    for (size_t k = 0; k < 3; ++k) {
      const Vertex& v = verts[order[i + k]];
      poly.push_back({mvp * v.pos, {v.uv[0], v.uv[1]}, v.colour});
    }
    poly = clip_polygon(std::move(poly));
    if (poly.empty()) {
      ++out_.stats.clipped_away;
      continue;
    }
    for (size_t k = 1; k + 1 < poly.size(); ++k) {
      auto rt = setup_triangle({to_window(poly[0]), to_window(poly[k]), to_window(poly[k + 1])}, W, H);
      if (!rt) {
        ++out_.stats.degenerate;
        continue;
      }
      // GL front faces turn counter-clockwise in window coordinates (y up), clockwise on the screen (y down).
      const bool front = st_.front_ccw ? !rt->clockwise : rt->clockwise;
      if (st_.cull && (st_.cull_mode == "GL_FRONT_AND_BACK" || (st_.cull_mode == "GL_FRONT") == front)) {
        ++out_.stats.culled;
        continue;
      }
      if (rt->xmin > rt->xmax || rt->ymin > rt->ymax) continue;
      DrawTriangle dt{*rt, 0.0};
      if (st_.offset_fill) {
        // GL 1.5 Sec. 3.5.5: factor * max(|dz/dx|, |dz/dy|) + units * r, r = one step of the 24-bit depth buffer.
        const ScreenVertex &a = rt->v[0], &b = rt->v[1], &cc = rt->v[2];
        const double det = (b.x - a.x) * (cc.y - a.y) - (cc.x - a.x) * (b.y - a.y);
        double dz = 0;
        if (det != 0) {
          const double dzdx = ((b.z - a.z) * (cc.y - a.y) - (cc.z - a.z) * (b.y - a.y)) / det;
          const double dzdy = ((cc.z - a.z) * (b.x - a.x) - (b.z - a.z) * (cc.x - a.x)) / det;
          dz = std::max(std::fabs(dzdx), std::fabs(dzdy));
        }
        dt.offset = st_.offset_factor * dz + st_.offset_units / kDepthMax;
      }
      ++out_.stats.rasterized;
      pd.triangles.push_back(dt);
    }
  }
  out_.draws.push_back(std::move(ops));
  out_.facts.push_back(draw_facts(pd.triangles.size()));
  pending_.push_back(std::move(pd));
}

// The sampler of a mipmapped texture object under the override, as ioquake3's r_textureMode sets
// GL_TEXTURE_MIN_FILTER and GL_TEXTURE_MAG_FILTER (the same base filter) of every mipmapped image and
// r_ext_max_anisotropy their GL_TEXTURE_MAX_ANISOTROPY_EXT.
void Replayer::override_sampler(SamplerDescriptor& sd) const {
  if (!filter_override_.empty()) {
    sd.mode.base = filter_override_.starts_with("GL_NEAREST") ? BaseFilter::Nearest : BaseFilter::Linear;
    sd.mode.mip = filter_override_.ends_with("MIPMAP_NEAREST") ? MipMode::Nearest : MipMode::Linear;
  }
  if (aniso_override_ != 0) sd.max_aniso = aniso_override_;
}

// The facts of the draw being submitted: its enabled units' texture objects, depth range,
// projection kind, modelview and place in a locked-arrays group.
DrawFacts Replayer::draw_facts(uint64_t triangles) {
  DrawFacts f;
  for (const UnitState& us : st_.units) {
    if (!us.enabled) continue;
    f.gl_textures.push_back(us.bound);
    const auto it = st_.textures.find(us.bound);
    f.min_filters.push_back(it == st_.textures.end() ? std::string() : it->second.min);
  }
  f.depth_near = st_.depth_near, f.depth_far = st_.depth_far;
  const glm::dmat4& p = st_.projection.back();
  f.orthographic = p[0][3] == 0 && p[1][3] == 0 && p[2][3] == 0 && p[3][3] == 1;  // GL column-major: row 3
  const glm::dmat4& mv = st_.modelview.back();
  const auto seen = std::find(modelviews_.begin(), modelviews_.end(), mv);
  f.modelview = static_cast<uint32_t>(seen - modelviews_.begin());
  if (seen == modelviews_.end()) modelviews_.push_back(mv);
  f.locked_pass = st_.locked ? locked_pass_++ : -1;
  f.triangles = triangles;
  return f;
}

void Replayer::execute(const Call& c) {
  const std::string& n = c.name;
  // Calls without an effect on the picture: window-system and context set-up, queries, frame ends.
  static const std::set<std::string> no_effect{
      "glXChooseVisual", "glXChooseFBConfig", "glXGetVisualFromFBConfig", "glXCreateContext", "glXCreateNewContext",
      "glXDestroyContext", "glXSwapBuffers", "glXQueryExtensionsString", "glXQueryVersion", "glXGetProcAddress",
      "glXGetProcAddressARB", "glXGetFBConfigAttrib", "glXGetConfig", "glXQueryDrawable", "glXGetCurrentContext",
      "glXGetCurrentDisplay", "glXGetCurrentDrawable", "glXGetClientString", "glXQueryServerString", "glXWaitGL", "glXWaitX",
      "glGetString", "glGetStringi", "glGetIntegerv", "glGetFloatv", "glGetBooleanv", "glGetError",
      "glGetFramebufferAttachmentParameteriv", "glFinish", "glFlush", "glGenTextures", "glHint"};
  if (n == "glXChooseVisual" || n == "glXChooseFBConfig") {
    // The visual's alpha bits: destination alpha exists only if the attribute list asks for them.
    const std::string& attribs = text(c, "attribList");
    const size_t p = attribs.find("GLX_ALPHA_SIZE, ");
    out_.destination_alpha = p != std::string::npos && std::atoi(attribs.c_str() + p + 16) > 0;
    return;
  }
  if (no_effect.contains(n)) return;
  if (n == "glXMakeCurrent" || n == "glXMakeContextCurrent") {
    const std::string& ctx = text(c, "ctx");
    if (ctx == "NULL") return;
    if (!context_.empty() && ctx != context_) st_ = State{};  // another context: its own (unshared) state
    context_ = ctx;
    return;
  }
  if (in_begin_ && n != "glVertex2f" && n != "glVertex3f" && n != "glVertex2fv" && n != "glVertex3fv" && n != "glTexCoord2f" &&
      n != "glTexCoord2fv" && n != "glColor4f" && n != "glColor3f" && n != "glColor4ub" && n != "glColor4ubv" &&
      n != "glColor4fv" && n != "glMultiTexCoord2f" && n != "glMultiTexCoord2fARB" && n != "glEnd")
    return unsupported(fmt::format("{} between glBegin and glEnd", n), c);
  if (n == "glEnable" || n == "glDisable") return enable(c, n == "glEnable");
  if (n == "glEnableClientState" || n == "glDisableClientState") return client_state(c, n == "glEnableClientState");
  if (n == "glActiveTexture" || n == "glActiveTextureARB" || n == "glClientActiveTexture" || n == "glClientActiveTextureARB") {
    const std::string& t = text(c, "texture");
    const int u = t == "GL_TEXTURE0" ? 0 : t == "GL_TEXTURE1" ? 1 : -1;
    if (u < 0) return unsupported(fmt::format("{}({})", n, t), c);
    (n.starts_with("glActive") ? st_.active : st_.client_active) = u;
    return;
  }
  if (n == "glBindTexture") {
    if (text(c, "target") != "GL_TEXTURE_2D") return unsupported(fmt::format("glBindTexture({})", text(c, "target")), c);
    st_.units[static_cast<size_t>(st_.active)].bound = static_cast<uint32_t>(int_arg(c, "texture", 0, std::numeric_limits<int>::max()));
    return;
  }
  if (n == "glDeleteTextures") {
    const Value& v = c.args.size() >= 2 ? c.args[1].second : c.arg("textures", Value::Kind::Number);
    std::vector<double> names = v.kind == Value::Kind::List ? v.list : std::vector<double>{v.number};
    if (v.kind != Value::Kind::List && v.kind != Value::Kind::Number) throw InputError(fmt::format("{}: unreadable texture names", where(c)));
    for (double name : names) {
      st_.textures.erase(static_cast<uint32_t>(name));
      for (UnitState& u : st_.units)
        if (u.bound == static_cast<uint32_t>(name)) u.bound = 0;
    }
    return;
  }
  if (n == "glTexImage2D") return tex_image(c);
  if (n == "glTexSubImage2D") return tex_sub_image(c);
  if (n == "glTexParameterf" || n == "glTexParameteri") return tex_parameter(c);
  if (n == "glTexEnvf" || n == "glTexEnvi") {
    if (text(c, "target") != "GL_TEXTURE_ENV" || text(c, "pname") != "GL_TEXTURE_ENV_MODE")
      return unsupported(fmt::format("{}({} {})", n, text(c, "target"), text(c, "pname")), c);
    st_.units[static_cast<size_t>(st_.active)].env = text(c, "param");
    return;
  }
  if (n == "glBlendFunc") {
    const auto s = blend_names().find(text(c, "sfactor")), d = blend_names().find(text(c, "dfactor"));
    if (s == blend_names().end() || d == blend_names().end() || d->second == BlendFactor::SrcAlphaSaturate)
      return unsupported(fmt::format("glBlendFunc({}, {})", text(c, "sfactor"), text(c, "dfactor")), c);
    st_.src = s->second, st_.dst = d->second;
    return;
  }
  if (n == "glDepthFunc" || n == "glAlphaFunc") {
    const auto f = compare_names().find(text(c, "func"));
    if (f == compare_names().end()) return unsupported(fmt::format("{}({})", n, text(c, "func")), c);
    if (n == "glDepthFunc") {
      st_.depth_func = f->second;
    } else {
      st_.alpha_func = f->second;
      st_.alpha_ref = std::clamp(c.number_arg("ref"), 0.0, 1.0);
    }
    return;
  }
  if (n == "glDepthMask") {
    st_.depth_write = text(c, "flag") != "GL_FALSE" && text(c, "flag") != "0";
    return;
  }
  if (n == "glDepthRange") {
    st_.depth_near = std::clamp(c.number_arg("zNear"), 0.0, 1.0);
    st_.depth_far = std::clamp(c.number_arg("zFar"), 0.0, 1.0);
    return;
  }
  if (n == "glPolygonOffset") {
    st_.offset_factor = c.number_arg("factor"), st_.offset_units = c.number_arg("units");
    return;
  }
  if (n == "glCullFace") {
    st_.cull_mode = text(c, "mode");
    return;
  }
  if (n == "glFrontFace") {
    st_.front_ccw = text(c, "mode") != "GL_CW";
    return;
  }
  if (n == "glViewport" || n == "glScissor") {
    const int x = int_arg(c, "x", -kMaxRenderSize, kMaxRenderSize), y = int_arg(c, "y", -kMaxRenderSize, kMaxRenderSize);
    const int w = int_arg(c, "width", 0, kMaxRenderSize), h = int_arg(c, "height", 0, kMaxRenderSize);
    if (n == "glViewport") st_.vp_x = x, st_.vp_y = y, st_.vp_w = w, st_.vp_h = h;
    else st_.sc_x = x, st_.sc_y = y, st_.sc_w = w, st_.sc_h = h;
    return;
  }
  if (n == "glClearColor") {
    st_.clear_colour = {c.number_arg("red"), c.number_arg("green"), c.number_arg("blue"), c.number_arg("alpha")};
    return;
  }
  if (n == "glClearDepth") {
    st_.clear_depth = std::clamp(c.number_arg("depth"), 0.0, 1.0);
    return;
  }
  if (n == "glClear") {
    if (in_frame_) clear(c);
    return;
  }
  if (n == "glMatrixMode") {
    const std::string& m = text(c, "mode");
    if (m != "GL_MODELVIEW" && m != "GL_PROJECTION") return unsupported(fmt::format("glMatrixMode({})", m), c);
    st_.matrix_mode = m;
    return;
  }
  if (n == "glLoadMatrixf" || n == "glLoadMatrixd" || n == "glMultMatrixf" || n == "glMultMatrixd") {
    const Value& v = c.arg("m", Value::Kind::List);
    if (v.list.size() != 16) throw InputError(fmt::format("{}: a matrix of {} values", where(c), v.list.size()));
    const glm::dmat4 m = glm::make_mat4(v.list.data());  // column-major, as GL
    current_matrix() = n.starts_with("glLoad") ? m : current_matrix() * m;
    return;
  }
  if (n == "glLoadIdentity") {
    current_matrix() = glm::dmat4(1.0);
    return;
  }
  if (n == "glOrtho") {
    current_matrix() *= glm::ortho(c.number_arg("left"), c.number_arg("right"), c.number_arg("bottom"), c.number_arg("top"),
                                   c.number_arg("zNear"), c.number_arg("zFar"));
    return;
  }
  if (n == "glTranslatef" || n == "glTranslated") {
    current_matrix() = glm::translate(current_matrix(), glm::dvec3(c.number_arg("x"), c.number_arg("y"), c.number_arg("z")));
    return;
  }
  if (n == "glScalef" || n == "glScaled") {
    current_matrix() = glm::scale(current_matrix(), glm::dvec3(c.number_arg("x"), c.number_arg("y"), c.number_arg("z")));
    return;
  }
  if (n == "glPushMatrix") {
    if (current_stack().size() >= 32) throw InputError(fmt::format("{}: matrix stack overflow", where(c)));
    current_stack().push_back(current_matrix());
    return;
  }
  if (n == "glPopMatrix") {
    if (current_stack().size() <= 1) throw InputError(fmt::format("{}: matrix stack underflow", where(c)));
    current_stack().pop_back();
    return;
  }
  if (n == "glColor4f" || n == "glColor3f") {
    st_.current_colour = {std::clamp(c.number_arg("red"), 0.0, 1.0) * 255.0, std::clamp(c.number_arg("green"), 0.0, 1.0) * 255.0,
                          std::clamp(c.number_arg("blue"), 0.0, 1.0) * 255.0,
                          n == "glColor3f" ? 255.0 : std::clamp(c.number_arg("alpha"), 0.0, 1.0) * 255.0};
    return;
  }
  if (n == "glColor4ub") {
    st_.current_colour = {c.number_arg("red"), c.number_arg("green"), c.number_arg("blue"), c.number_arg("alpha")};
    return;
  }
  if (n == "glColor4ubv" || n == "glColor4fv") {
    const Value& v = c.arg("v", Value::Kind::List);
    if (v.list.size() != 4) throw InputError(fmt::format("{}: expected 4 values", where(c)));
    const double scale = n == "glColor4fv" ? 255.0 : 1.0;
    for (int k = 0; k < 4; ++k) st_.current_colour[k] = std::clamp(v.list[static_cast<size_t>(k)] * scale, 0.0, 255.0);
    return;
  }
  if (n == "glTexCoord2f") {
    st_.units[0].current = {c.number_arg("s"), c.number_arg("t")};
    return;
  }
  if (n == "glMultiTexCoord2f" || n == "glMultiTexCoord2fARB") {
    const std::string& t = text(c, "target");
    const int u = t == "GL_TEXTURE0" ? 0 : t == "GL_TEXTURE1" ? 1 : -1;
    if (u < 0) return unsupported(fmt::format("{}({})", n, t), c);
    st_.units[static_cast<size_t>(u)].current = {c.number_arg("s"), c.number_arg("t")};
    return;
  }
  if (n == "glVertex2f" || n == "glVertex3f") {
    if (!in_begin_) return unsupported(fmt::format("{} outside glBegin/glEnd", n), c);
    Vertex v;
    v.pos = {c.number_arg("x"), c.number_arg("y"), n == "glVertex3f" ? c.number_arg("z") : 0.0, 1.0};
    v.uv = {st_.units[0].current, st_.units[1].current};
    v.colour = st_.current_colour;
    if (immediate_.size() >= (size_t{1} << 20)) throw InputError(fmt::format("{}: more than 2^20 vertices in one glBegin", where(c)));
    immediate_.push_back(v);
    return;
  }
  // The vector forms of the immediate-mode calls (the engine's sky box): the values as a list.
  if (n == "glTexCoord2fv") {
    const Value& v = c.arg("v", Value::Kind::List);
    if (v.list.size() != 2) throw InputError(fmt::format("{}: expected 2 values", where(c)));
    st_.units[0].current = {v.list[0], v.list[1]};
    return;
  }
  if (n == "glVertex2fv" || n == "glVertex3fv") {
    if (!in_begin_) return unsupported(fmt::format("{} outside glBegin/glEnd", n), c);
    const Value& l = c.arg("v", Value::Kind::List);
    const size_t k = n == "glVertex3fv" ? 3 : 2;
    if (l.list.size() != k) throw InputError(fmt::format("{}: expected {} values", where(c), k));
    Vertex v;
    v.pos = {l.list[0], l.list[1], k == 3 ? l.list[2] : 0.0, 1.0};
    v.uv = {st_.units[0].current, st_.units[1].current};
    v.colour = st_.current_colour;
    if (immediate_.size() >= (size_t{1} << 20))
      throw InputError(fmt::format("{}: more than 2^20 vertices in one glBegin", where(c)));
    immediate_.push_back(v);
    return;
  }
  if (n == "glBegin") {
    in_begin_ = true;
    begin_mode_ = text(c, "mode");
    immediate_.clear();
    return;
  }
  if (n == "glEnd") {
    if (!in_begin_) return unsupported("glEnd without glBegin", c);
    return end_immediate(c);
  }
  if (n == "glVertexPointer") return set_pointer(c, st_.vertex, {2, 3, 4}, {"GL_FLOAT"});
  if (n == "glColorPointer") return set_pointer(c, st_.colour, {3, 4}, {"GL_UNSIGNED_BYTE", "GL_FLOAT"});
  if (n == "glTexCoordPointer") return set_pointer(c, st_.units[static_cast<size_t>(st_.client_active)].texcoord, {2}, {"GL_FLOAT"});
  if (n == "glLockArraysEXT") {
    st_.locked = true;
    st_.lock_first = int_arg(c, "first", 0, 1 << 26), st_.lock_count = int_arg(c, "count", 0, 1 << 26);
    locked_pass_ = 0;
    return;
  }
  if (n == "glUnlockArraysEXT") {
    st_.locked = false;
    return;
  }
  if (n == "glDrawElements") {
    if (in_frame_) draw_elements(c);
    return;
  }
  if (n == "glDrawArrays") {
    if (in_frame_) draw_arrays(c);
    return;
  }
  // Accepted only in the state the renderer assumes.
  if (n == "glShadeModel" && text(c, "mode") == "GL_SMOOTH") return;
  if (n == "glPolygonMode" && text(c, "mode") == "GL_FILL") return;
  if (n == "glDrawBuffer" && (text(c, "mode") == "GL_BACK" || text(c, "mode") == "GL_BACK_LEFT")) return;
  if (n == "glColorMask" && text(c, "red") == "GL_TRUE" && text(c, "green") == "GL_TRUE" && text(c, "blue") == "GL_TRUE") return;
  unsupported(n, c);
}

void Replayer::rasterize(const GoldenUnit& golden) {
  const int W = out_.width, H = out_.height;
  Image& colour = out_.image;
  std::vector<uint32_t> depth(static_cast<size_t>(W) * static_cast<size_t>(H), kDepthMax);
  size_t next_clear = 0;
  std::vector<Rgba8> texels;
  for (size_t di = 0; di < pending_.size(); ++di) {
    while (next_clear < out_.clears.size() && out_.clears[next_clear].before_draw <= di) apply_clear(out_.clears[next_clear++], colour, depth);
    const PendingDraw& pd = pending_[di];
    const DrawOps& ops = out_.draws[di];
    const auto [rx0, ry0, rx1, ry1] = pd.rect;
    for (const DrawTriangle& dt : pd.triangles) {
      const RasterTriangle& tri = dt.tri;
      const int qy_first = std::max(tri.ymin, ry0) & ~1, qy_last = std::min(tri.ymax, ry1 - 1);
      const int qx_first = std::max(tri.xmin, rx0) & ~1, qx_last = std::min(tri.xmax, rx1 - 1);
      for (int qy = qy_first; qy <= qy_last; qy += 2)
        for (int qx = qx_first; qx <= qx_last; qx += 2) {
          FragmentQuad q;
          q.draw = static_cast<uint32_t>(di);
          q.x = static_cast<uint16_t>(qx), q.y = static_cast<uint16_t>(qy);
          std::array<std::array<double, 3>, 4> b;
          for (size_t k = 0; k < 4; ++k) {
            const int px = qx + static_cast<int>(k & 1), py = qy + static_cast<int>(k >> 1);
            b[k] = tri.barycentric(RasterTriangle::centre(px), RasterTriangle::centre(py));
            if (px < rx0 || px >= rx1 || py < ry0 || py >= ry1 || !tri.covers_pixel(px, py)) continue;
            const double z = b[k][0] * tri.v[0].z + b[k][1] * tri.v[1].z + b[k][2] * tri.v[2].z + dt.offset;
            q.depth[k] = depth_code(z);
            const size_t idx = static_cast<size_t>(py) * static_cast<size_t>(W) + static_cast<size_t>(px);
            if (ops.depth_test && !compare(ops.depth_func, q.depth[k], depth[idx])) continue;
            q.mask = static_cast<uint8_t>(q.mask | (1u << k));
          }
          if (q.mask == 0) continue;
          for (size_t k = 0; k < 4; ++k)
            if (q.mask >> k & 1u) q.primary[k] = primary_colour(tri, b[k]);
          q.first_request = static_cast<uint32_t>(out_.requests.requests.size());
          if (out_.requests.requests.size() + 4 * pd.stages.size() > kMaxTraceRequests)
            throw InputError(fmt::format("--gl-trace '{}': frame {} makes more than {} requests", quote_path(out_.trace), out_.frame,
                                         kMaxTraceRequests));
          texels.assign(4 * pd.stages.size(), Rgba8{});
          for (size_t st = 0; st < pd.stages.size(); ++st) {
            const size_t first = out_.requests.requests.size();
            for (size_t k = 0; k < 4; ++k) {
              const glm::dvec2 uv = interpolate_st(tri, b[k], pd.uv_units[st]);
              TraceRequest r;
              r.texture = static_cast<uint16_t>(pd.stages[st].texture);
              r.sampler = static_cast<uint8_t>(pd.stages[st].sampler);
              r.stage = static_cast<uint8_t>(st);
              r.s = static_cast<float>(std::clamp(uv.x, -1e30, 1e30));
              r.t = static_cast<float>(std::clamp(uv.y, -1e30, 1e30));
              out_.requests.requests.push_back(r);
            }
            // The golden model on the covered pixels: its LOD unit on the quad, its sampler.
            if (pd.anisotropic[st]) {
              const AnisoLod lod = golden.lod(out_.requests, first);
              for (size_t k = 0; k < 4; ++k)
                if (q.mask >> k & 1u) texels[st * 4 + k] = golden.sample(out_.requests.requests[first + k], lod);
            } else {
              const int32_t lambda = golden.lambda(out_.requests, first);
              for (size_t k = 0; k < 4; ++k)
                if (q.mask >> k & 1u) texels[st * 4 + k] = golden.sample(out_.requests.requests[first + k], lambda);
            }
          }
          apply_quad(ops, q, texels.data(), out_.destination_alpha, colour, depth);
          out_.quads.push_back(q);
          ++out_.stats.quads;
          out_.stats.pixels += static_cast<uint64_t>(std::popcount(q.mask));
        }
    }
  }
  while (next_clear < out_.clears.size()) apply_clear(out_.clears[next_clear++], colour, depth);
}

Replay Replayer::run() {
  const Stream& s = dump_.stream();
  // The framebuffer: the extent of the frame's viewports (the window the engine draws into).
  for (size_t i = s.frame_begin; i < s.calls.size(); ++i)
    if (s.calls[i].name == "glViewport") {
      const Call& c = s.calls[i];
      out_.width = std::max(out_.width, int_arg(c, "x", 0, kMaxRenderSize) + int_arg(c, "width", 0, kMaxRenderSize));
      out_.height = std::max(out_.height, int_arg(c, "y", 0, kMaxRenderSize) + int_arg(c, "height", 0, kMaxRenderSize));
    }
  if (out_.width < 1 || out_.height < 1 || out_.width > kMaxRenderSize || out_.height > kMaxRenderSize)
    throw InputError(fmt::format("--gl-trace '{}': frame {} sets no viewport of 1..{} pixels", quote_path(out_.trace), out_.frame,
                                 kMaxRenderSize));
  out_.times.dump_wall = s.dump_wall_seconds;
  out_.times.dump_cpu = s.dump_cpu_seconds;
  out_.times.parse = s.parse_cpu_seconds;
  const double t_state = thread_seconds();
  for (size_t i = 0; i < s.calls.size(); ++i) {
    in_frame_ = i >= s.frame_begin;
    try {
      execute(s.calls[i]);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      throw InputError(msg.find("--gl-trace") == 0 ? msg : fmt::format("--gl-trace '{}': {}", quote_path(out_.trace), msg));
    }
  }
  out_.first_call = s.frame_begin < s.calls.size() ? s.calls[s.frame_begin].number : 0;
  out_.last_call = s.calls.empty() ? 0 : s.calls.back().number;
  out_.stats.calls = s.calls.size();
  out_.stats.frame_calls = s.calls.size() - s.frame_begin;
  if (!unsupported_.empty()) {
    std::string list;
    for (const std::string& u : unsupported_) list += (list.empty() ? "" : ", ") + u;
    throw InputError(one_line(fmt::format("--gl-trace '{}': unsupported GL calls or states: {}", quote_path(out_.trace), list)));
  }
  if (alpha_bits_ >= 0) out_.destination_alpha = alpha_bits_ > 0;
  const double t_place = thread_seconds();
  out_.times.state = t_place - t_state;
  out_.unit_frame = std::make_shared<const Frame>(builder_.finish());
  out_.stats.textures = out_.unit_frame->textures.size();
  out_.stats.samplers = out_.unit_frame->regs.samplers.size();
  out_.image = Image(out_.width, out_.height, Rgba8{0, 0, 0, 255});
  out_.requests.mode = TraceMode::Quad;
  out_.requests.source = out_.trace;
  const GoldenUnit golden(*out_.unit_frame);
  const double t_raster = thread_seconds();
  out_.times.place = t_raster - t_place;
  rasterize(golden);
  out_.times.raster = thread_seconds() - t_raster;
  return std::move(out_);
}

}  // namespace

Replay replay_frame(const std::string& trace, int frame, const ReplayOptions& opts) {
  // The sampler override, checked before apitrace runs: a GL minification filter with MIP levels,
  // an anisotropy 1..16 (0: as traced).
  static const std::set<std::string> mip_filters{"GL_NEAREST_MIPMAP_NEAREST", "GL_LINEAR_MIPMAP_NEAREST",
                                                 "GL_NEAREST_MIPMAP_LINEAR", "GL_LINEAR_MIPMAP_LINEAR"};
  if (!opts.min_filter.empty() && !mip_filters.contains(opts.min_filter))
    throw InputError(
        fmt::format("--gl-min-filter '{}': expected a filter with MIP levels: GL_NEAREST_MIPMAP_NEAREST, "
                    "GL_LINEAR_MIPMAP_NEAREST, GL_NEAREST_MIPMAP_LINEAR or GL_LINEAR_MIPMAP_LINEAR",
                    quote_input(opts.min_filter, 60)));
  if (opts.max_aniso < 0 || opts.max_aniso > 16)
    throw InputError(fmt::format("--gl-max-aniso {}: expected 1..16 (0: as traced)", opts.max_aniso));
  const Dump dump(trace, frame);
  Replayer r(dump, frame, opts);
  return r.run();
}

void write_draw_table(const Replay& r, std::ostream& os) {
  std::vector<uint64_t> quads(r.draws.size()), pixels(r.draws.size());
  for (const FragmentQuad& q : r.quads) ++quads[q.draw], pixels[q.draw] += static_cast<uint64_t>(std::popcount(q.mask));
  // Names as GL spells them (the replay's own tables, read backwards).
  const auto gl_name = [](const auto& table, auto v) {
    for (const auto& [name, value] : table)
      if (value == v) return name;
    return std::string("?");
  };
  os << "draw,call,stages,gl_textures,min_filters,envs,blend,src,dst,alpha_test,depth_test,depth_func,depth_write,"
        "depth_near,depth_far,orthographic,modelview,locked_pass,triangles,quads,pixels,requests\n";
  const auto joined = [](const auto& v, const auto& name) {
    std::string out;
    for (const auto& x : v) {
      if (!out.empty()) out += ' ';
      out += name(x);
    }
    return out;
  };
  for (size_t i = 0; i < r.draws.size(); ++i) {
    const DrawOps& d = r.draws[i];
    const DrawFacts& f = r.facts[i];
    const auto env_of = [](const StageEnv& e) { return std::string(kTexEnvNames.name(e.combine.env)); };
    os << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", i, d.call, d.stages.size(),
                      joined(f.gl_textures, [](uint32_t t) { return std::to_string(t); }),
                      joined(f.min_filters, [](const std::string& m) { return m; }), joined(d.stages, env_of),
                      d.blend ? 1 : 0, gl_name(blend_names(), d.src), gl_name(blend_names(), d.dst),
                      d.alpha_test ? 1 : 0, d.depth_test ? 1 : 0, gl_name(compare_names(), d.depth_func),
                      d.depth_write ? 1 : 0, f.depth_near, f.depth_far, f.orthographic ? 1 : 0, f.modelview,
                      f.locked_pass, f.triangles, quads[i], pixels[i], 4 * quads[i] * d.stages.size());
  }
}

Image compose_frame(const Replay& r, const std::vector<Rgba8>& outputs) {
  if (outputs.size() != r.requests.requests.size())
    throw InputError(fmt::format("compose_frame: {} outputs for {} requests", outputs.size(), r.requests.requests.size()));
  Image colour(r.width, r.height, Rgba8{0, 0, 0, 255});
  std::vector<uint32_t> depth(static_cast<size_t>(r.width) * static_cast<size_t>(r.height), kDepthMax);
  size_t next_clear = 0;
  for (const FragmentQuad& q : r.quads) {
    while (next_clear < r.clears.size() && r.clears[next_clear].before_draw <= q.draw) apply_clear(r.clears[next_clear++], colour, depth);
    apply_quad(r.draws[q.draw], q, outputs.data() + q.first_request, r.destination_alpha, colour, depth);
  }
  while (next_clear < r.clears.size()) apply_clear(r.clears[next_clear++], colour, depth);
  return colour;
}

}  // namespace tfu::gl
