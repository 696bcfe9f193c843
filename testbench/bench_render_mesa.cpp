// The golden renderer against Mesa's llvmpipe on the same work (docs/performance.md, "Renderer
// against llvmpipe"): one scene drawn by `render_scene` (cmodel/raster.hpp) and by Mesa 22.3.6
// through OSMesa (Debian libosmesa6), same geometry, resolution, textures and MIP chains, filters,
// texture environments and depth test, timed draw only, best of N.
//
//   tfu_bench_render_mesa [--scene NAME] [--width W] [--height H] [--threads T] [--reps N]
//                         [--driver llvmpipe|softpipe] [--game-dir DIR] [--out-prefix P]
//
// Threads: T threads for the golden renderer (its bands, RenderOptions::threads) and for llvmpipe
// LP_NUM_THREADS = T, except T = 1, where LP_NUM_THREADS = 0: llvmpipe rasterizes on the calling
// thread, no worker (LP_NUM_THREADS = 1 would be one worker plus the calling thread). The variable is
// read when the first context is made, so one thread count per process (scripts/render-vs-llvmpipe
// runs the counts).
//
// What each side's time includes (wall clock, std::chrono::steady_clock, and the process's CPU
// seconds over the same span, std::clock: all its threads', llvmpipe's workers included; on a loaded
// machine the steadier figure, at one thread the same work as the wall time):
//   golden   RenderResult::times.draw: transform, clipping and setup of the scene's triangles, the
//            colour and depth buffers cleared (the frames drawn into one RenderResult, whose buffers'
//            memory is reused as llvmpipe keeps its framebuffer: cleared, not allocated and
//            page-faulted per frame), every band rasterized and shaded (LOD, golden sampler,
//            texture environment, display ramp, depth), the band outputs gathered; not the upload
//            (descriptors, texel memory, samplers: times.upload, shown apart).
//   Mesa     glClear of colour and depth, every mesh's state (texture units, environment) and
//            glDrawElements from vertex buffers, then glFinish, which with OSMesa also copies the
//            picture into the caller's buffer (the read-back: included, as the golden renderer
//            writes its image in place). Textures and vertex buffers are uploaded before the clock.
// Each side runs once untimed first (llvmpipe compiles its shaders on the first draw), then N timed
// repetitions; best and median are printed. An untimed Mesa pass with an occlusion query counts the
// fragments that passed the depth test, to hold against the golden renderer's shaded pixels, and the
// two pictures are compared (PSNR, pixels differing): the LOD and filter rounding differ, the work
// does not.
//
// Mapping of a scene to GL 1.x fixed function: stage k of a mesh on texture unit k with GL_COMBINE
// (replace: REPLACE of the texture; modulate: MODULATE of previous and texture; add: ADD, alpha
// MODULATE; decal: INTERPOLATE of texture and previous by the texture's alpha, alpha of previous),
// GL_RGB_SCALE the stage's scale; the display ramp (Scene::display_shift) as the last stage's
// GL_RGB_SCALE when the product is at most 4, else one more unit (a 1 x 1 white texture, REPLACE of
// previous, scaled); the primary colour glColor per vertex for vertex-coloured meshes, white
// otherwise; culling by Scene::cull (a winding as seen on the screen: clockwise ones are GL's back
// faces with glFrontFace(GL_CCW), glCullFace(GL_BACK)); depth GL_LESS, 24 bits (the
// golden renderer keeps float z). Filters: NEAREST/LINEAR with MIPMAP_NEAREST/LINEAR, maxAniso as
// GL_TEXTURE_MAX_ANISOTROPY_EXT; CUBIC and EDGE_PRESERVING have no GL counterpart and are refused.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "cmodel/error.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"

namespace {

using tfu::InputError;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string scene = "ground_plane";
  int width = 1024, height = 768;
  int threads = 1;
  int reps = 7;
  std::string driver = "llvmpipe";
  std::string game_dir;
  std::string out_prefix;  // non-empty: write PREFIX-golden.png and PREFIX-mesa.png
};

int int_arg(const char* name, const char* v, int lo, int hi) {
  char* end = nullptr;
  const long x = std::strtol(v, &end, 10);
  if (end == v || *end != '\0' || x < lo || x > hi)
    throw InputError(fmt::format("{} '{}': expected an integer in {}..{}", name, v, lo, hi));
  return static_cast<int>(x);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc)
      throw InputError(fmt::format("{}: missing value (usage: see testbench/bench_render_mesa.cpp)", a));
    const char* v = argv[++i];
    if (a == "--scene")
      o.scene = v;
    else if (a == "--width")
      o.width = int_arg("--width", v, 1, tfu::kMaxRenderSize);
    else if (a == "--height")
      o.height = int_arg("--height", v, 1, tfu::kMaxRenderSize);
    else if (a == "--threads")
      o.threads = int_arg("--threads", v, 1, 64);
    else if (a == "--reps")
      o.reps = int_arg("--reps", v, 1, 1000);
    else if (a == "--driver")
      o.driver = v;
    else if (a == "--game-dir")
      o.game_dir = v;
    else if (a == "--out-prefix")
      o.out_prefix = v;
    else
      throw InputError(fmt::format("unknown option '{}' (usage: see testbench/bench_render_mesa.cpp)", a));
  }
  if (o.driver != "llvmpipe" && o.driver != "softpipe")
    throw InputError(fmt::format("--driver '{}': llvmpipe or softpipe", o.driver));
  return o;
}

struct Times {
  double best = 0, median = 0;
};
Times summarize(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2]};
}

// ---- Mesa side ----

GLenum gl_wrap(tfu::WrapMode m) {
  switch (m) {
    case tfu::WrapMode::Repeat: return GL_REPEAT;
    case tfu::WrapMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
    case tfu::WrapMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
    case tfu::WrapMode::ClampToBorder: return GL_CLAMP_TO_BORDER;
  }
  return GL_REPEAT;
}

GLenum gl_min_filter(tfu::FilterMode f) {
  const bool lin = f.base == tfu::BaseFilter::Linear;
  switch (f.mip) {
    case tfu::MipMode::None: return lin ? GL_LINEAR : GL_NEAREST;
    case tfu::MipMode::Nearest: return lin ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case tfu::MipMode::Linear: return lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
  }
  return GL_LINEAR;
}

struct GlMesh {
  GLuint vbo = 0, ibo = 0;
  GLsizei indices = 0;
  size_t stride = 0;  // floats per vertex: x y z, s0 t0, s1 t1, r g b a
};

class MesaScene {
 public:
  MesaScene(const tfu::Scene& scene, const std::string& driver, int threads) : scene_(scene) {
    setenv("GALLIUM_DRIVER", driver.c_str(), 1);
    setenv("LP_NUM_THREADS", std::to_string(threads == 1 ? 0 : threads).c_str(), 1);
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_COMPAT_PROFILE,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (ctx_ == nullptr) throw InputError("OSMesaCreateContextAttribs failed (Debian libosmesa6)");
    buffer_.assign(static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height) * 4, 0);
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, scene.width, scene.height))
      throw InputError("OSMesaMakeCurrent failed");
    OSMesaPixelStore(OSMESA_Y_UP, 0);  // row 0 on top, as the golden image
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (renderer_.find(driver) == std::string::npos)
      throw InputError(fmt::format("GL_RENDERER '{}' is not {}", renderer_, driver));
    GLint units = 0;
    glGetIntegerv(GL_MAX_TEXTURE_UNITS, &units);
    max_units_ = units;
    upload();
  }
  ~MesaScene() {
    if (ctx_ != nullptr) OSMesaDestroyContext(ctx_);
  }
  MesaScene(const MesaScene&) = delete;
  MesaScene& operator=(const MesaScene&) = delete;

  const std::string& renderer() const { return renderer_; }

  // One frame: clear, every mesh, glFinish (the picture is then in buffer_).
  void draw() {
    glClearColor(static_cast<GLfloat>(scene_.background[0]), static_cast<GLfloat>(scene_.background[1]),
                 static_cast<GLfloat>(scene_.background[2]), static_cast<GLfloat>(scene_.background[3]));
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (size_t m = 0; m < scene_.meshes.size(); ++m) draw_mesh(m);
    glFinish();
  }

  // Fragments that passed the depth test in one frame (an occlusion query around the draws).
  int64_t passed_fragments() {
    GLuint q = 0;
    glGenQueries(1, &q);
    glBeginQuery(GL_SAMPLES_PASSED, q);
    draw();
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint n = 0;  // GL 1.5's 32-bit result: enough for any frame here (< 2^32 fragments)
    glGetQueryObjectuiv(q, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &q);
    return static_cast<int64_t>(n);
  }

  tfu::Image image() const {
    tfu::Image im(scene_.width, scene_.height);
    std::memcpy(im.texels.data(), buffer_.data(), buffer_.size());
    return im;
  }

 private:
  void upload() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glViewport(0, 0, scene_.width, scene_.height);
    glMatrixMode(GL_PROJECTION);
    const glm::dmat4 proj = tfu::projection_matrix(scene_.camera, static_cast<double>(scene_.width) / scene_.height);
    glLoadMatrixd(glm::value_ptr(proj));
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(glm::value_ptr(tfu::view_matrix(scene_.camera)));
    if (scene_.cull != tfu::CullWinding::None) {
      glEnable(GL_CULL_FACE);
      glFrontFace(GL_CCW);
      glCullFace(scene_.cull == tfu::CullWinding::Clockwise ? GL_BACK : GL_FRONT);
    }
    const uint8_t white[4] = {255, 255, 255, 255};
    glGenTextures(1, &white_);
    glBindTexture(GL_TEXTURE_2D, white_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
    for (const tfu::Mesh& mesh : scene_.meshes) {
      if (mesh.stages.size() + 1 > static_cast<size_t>(max_units_))
        throw InputError(
            fmt::format("a mesh of {} stages: Mesa offers {} texture units", mesh.stages.size(), max_units_));
      for (const tfu::TextureStage& st : mesh.stages) {
        if (st.sampler.mode.base == tfu::BaseFilter::Cubic || st.sampler.mode.base == tfu::BaseFilter::EdgePreserving)
          throw InputError(fmt::format("filter {} has no GL counterpart (nearest and linear modes only)",
                                       tfu::filter_mode_name(st.sampler.mode)));
        if (textures_.count(st.texture.get()) > 0) continue;
        GLuint name = 0;
        glGenTextures(1, &name);
        glBindTexture(GL_TEXTURE_2D, name);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        const GLenum internal = st.texture->format == tfu::TexelFormat::SRGBA8 ? GL_SRGB8_ALPHA8 : GL_RGBA8;
        for (size_t l = 0; l < st.texture->levels.size(); ++l) {
          const tfu::Image& im = st.texture->levels[l];
          glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(l), static_cast<GLint>(internal), im.width, im.height, 0,
                       GL_RGBA, GL_UNSIGNED_BYTE, im.texels.data());
        }
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, st.texture->max_level());
        textures_[st.texture.get()] = name;
      }
      GlMesh g;
      g.stride = 11;
      std::vector<float> v;
      v.reserve(mesh.vertices.size() * g.stride);
      for (const tfu::Vertex& x : mesh.vertices)
        for (double c : {x.pos.x, x.pos.y, x.pos.z, x.uv.x, x.uv.y, x.uv1.x, x.uv1.y, x.colour.r / 255.0,
                         x.colour.g / 255.0, x.colour.b / 255.0, x.colour.a / 255.0})
          v.push_back(static_cast<float>(c));
      std::vector<uint32_t> idx;
      for (const auto& t : mesh.triangles) idx.insert(idx.end(), t.begin(), t.end());
      g.indices = static_cast<GLsizei>(idx.size());
      glGenBuffers(1, &g.vbo);
      glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
      glGenBuffers(1, &g.ibo);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
      glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(uint32_t)), idx.data(),
                   GL_STATIC_DRAW);
      meshes_.push_back(g);
    }
    glFinish();
  }

  void set_unit(int unit, GLuint texture, const tfu::SamplerDescriptor* s, tfu::TexEnv env, int scale,
                GLintptr uv_offset, GLsizei stride_bytes) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glClientActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, texture);
    if (s != nullptr) {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_min_filter(s->mode)));
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER,
                      s->mode.base == tfu::BaseFilter::Linear ? GL_LINEAR : GL_NEAREST);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<GLint>(gl_wrap(s->wrap_s)));
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, static_cast<GLint>(gl_wrap(s->wrap_t)));
      const GLfloat border[4] = {s->border.r / 255.f, s->border.g / 255.f, s->border.b / 255.f, s->border.a / 255.f};
      glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
      glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_LOD_BIAS, static_cast<GLfloat>(s->lod.bias_q8 / 256.0));
      glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_LOD, static_cast<GLfloat>(s->lod.min_lod_q8 / 256.0));
      glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_LOD, static_cast<GLfloat>(s->lod.max_lod_q8 / 256.0));
      glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, static_cast<GLfloat>(s->max_aniso));
    }
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_COMBINE);
    GLint rgb = GL_REPLACE, alpha = GL_REPLACE;
    GLint src[3] = {GL_TEXTURE, GL_PREVIOUS, GL_TEXTURE}, asrc0 = GL_TEXTURE;
    switch (env) {
      case tfu::TexEnv::Replace: break;
      case tfu::TexEnv::Modulate: rgb = alpha = GL_MODULATE; break;
      case tfu::TexEnv::Add: rgb = GL_ADD, alpha = GL_MODULATE; break;
      case tfu::TexEnv::Decal: rgb = GL_INTERPOLATE, asrc0 = GL_PREVIOUS; break;
    }
    if (s == nullptr) src[0] = GL_PREVIOUS, asrc0 = GL_PREVIOUS;  // the display-ramp unit
    glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_RGB, rgb);
    glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_ALPHA, alpha);
    glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE0_RGB, src[0]);
    glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE1_RGB, src[1]);
    glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE2_RGB, src[2]);
    glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_RGB, GL_SRC_COLOR);
    glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND1_RGB, GL_SRC_COLOR);
    glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND2_RGB, GL_SRC_ALPHA);
    glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE0_ALPHA, asrc0);
    glTexEnvi(GL_TEXTURE_ENV, GL_SOURCE1_ALPHA, GL_PREVIOUS);
    glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_ALPHA, GL_SRC_ALPHA);
    glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND1_ALPHA, GL_SRC_ALPHA);
    glTexEnvf(GL_TEXTURE_ENV, GL_RGB_SCALE, static_cast<GLfloat>(scale));
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    glTexCoordPointer(2, GL_FLOAT, stride_bytes, reinterpret_cast<const void*>(uv_offset));
  }

  void draw_mesh(size_t m) {
    const tfu::Mesh& mesh = scene_.meshes[m];
    const GlMesh& g = meshes_[m];
    const auto stride = static_cast<GLsizei>(g.stride * sizeof(float));
    glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, stride, nullptr);
    if (mesh.vertex_colour) {
      glEnableClientState(GL_COLOR_ARRAY);
      glColorPointer(4, GL_FLOAT, stride, reinterpret_cast<const void*>(7 * sizeof(float)));
    } else {
      glDisableClientState(GL_COLOR_ARRAY);
      glColor4f(1, 1, 1, 1);
    }
    const int ramp = 1 << scene_.display_shift;
    const int n = static_cast<int>(mesh.stages.size());
    const int last_scale = mesh.stages.back().combine.rgb_scale * ramp;
    const bool ramp_unit = ramp > 1 && last_scale > 4;
    for (int k = 0; k < n; ++k) {
      const tfu::TextureStage& st = mesh.stages[static_cast<size_t>(k)];
      const int scale = st.combine.rgb_scale * (k + 1 == n && !ramp_unit ? ramp : 1);
      set_unit(k, textures_.at(st.texture.get()), &st.sampler, st.combine.env, scale,
               static_cast<GLintptr>((st.uv_set == 0 ? 3 : 5) * sizeof(float)), stride);
    }
    int units = n;
    if (ramp_unit) set_unit(units++, white_, nullptr, tfu::TexEnv::Replace, ramp, 0, stride);
    for (int k = units; k < used_units_; ++k) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + k));
      glClientActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + k));
      glDisable(GL_TEXTURE_2D);
      glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    }
    used_units_ = units;
    glDrawElements(GL_TRIANGLES, g.indices, GL_UNSIGNED_INT, nullptr);
  }

  const tfu::Scene& scene_;
  OSMesaContext ctx_ = nullptr;
  std::vector<uint8_t> buffer_;
  std::string renderer_;
  int max_units_ = 0, used_units_ = 0;
  GLuint white_ = 0;
  std::map<const tfu::Texture*, GLuint> textures_;
  std::vector<GlMesh> meshes_;
};

// PSNR (dB, RGB) and the count of pixels whose largest channel difference exceeds 8 codes.
std::pair<double, int64_t> compare(const tfu::Image& a, const tfu::Image& b) {
  double se = 0;
  int64_t far = 0;
  for (size_t i = 0; i < a.texels.size(); ++i) {
    const tfu::Rgba8 x = a.texels[i], y = b.texels[i];
    int worst = 0;
    for (const auto& [p, q] : {std::pair{x.r, y.r}, {x.g, y.g}, {x.b, y.b}}) {
      const int d = int{p} - int{q};
      se += d * d;
      worst = std::max(worst, std::abs(d));
    }
    far += worst > 8;
  }
  const double mse = se / (3.0 * static_cast<double>(a.texels.size()));
  return {mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : INFINITY, far};
}

int run(const Options& o) {
  const tfu::Scene scene = tfu::open_scene({o.scene, o.width, o.height, o.game_dir});
  int64_t triangles = 0;
  for (const tfu::Mesh& m : scene.meshes) triangles += static_cast<int64_t>(m.triangles.size());

  // Golden renderer: one untimed render, then the timed ones.
  tfu::RenderOptions ro;
  ro.threads = o.threads;
  // Frame after frame into the same result, whose colour and depth buffers are reused (as Mesa
  // keeps its framebuffer): each frame clears them rather than allocating them.
  tfu::RenderResult golden = tfu::render_scene(scene, ro);
  std::vector<double> draw, draw_cpu, upload;
  for (int r = 0; r < o.reps; ++r) {
    tfu::render_scene(scene, ro, golden);
    draw.push_back(golden.times.draw);
    draw_cpu.push_back(golden.times.draw_cpu);
    upload.push_back(golden.times.upload);
  }
  const Times g = summarize(draw), gc = summarize(draw_cpu), gu = summarize(upload);

  MesaScene mesa(scene, o.driver, o.threads);
  const int64_t fragments = mesa.passed_fragments();  // also the untimed first frame
  std::vector<double> mt, mc;
  for (int r = 0; r < o.reps; ++r) {
    const Clock::time_point t0 = Clock::now();
    const std::clock_t c0 = std::clock();
    mesa.draw();
    mc.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    mt.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  const Times m = summarize(mt), mcpu = summarize(mc);
  const tfu::Image mesa_image = mesa.image();
  const auto [psnr, far] = compare(golden.image, mesa_image);
  if (!o.out_prefix.empty()) {
    tfu::OutputFiles outputs(true);
    outputs.add_image("--out-prefix", o.out_prefix + "-golden.png").write_image(golden.image);
    outputs.add_image("--out-prefix", o.out_prefix + "-mesa.png").write_image(mesa_image);
    outputs.commit();
  }
  fmt::print(
      "{} {}x{}, {} triangles, threads {}: golden draw best {:.2f} ms wall (median {:.2f}), {:.2f} ms CPU (median "
      "{:.2f}; upload {:.2f} ms apart); {} draw best {:.2f} ms wall (median {:.2f}), {:.2f} ms CPU (median {:.2f}); "
      "golden / {} = {:.2f} wall, {:.2f} CPU; shaded pixels golden {} / Mesa depth-passed fragments {}; PSNR golden "
      "vs Mesa {:.1f} dB, {} pixels differ by > 8 codes; {}\n",
      scene.name, scene.width, scene.height, triangles, o.threads, g.best * 1e3, g.median * 1e3, gc.best * 1e3,
      gc.median * 1e3, gu.best * 1e3, o.driver, m.best * 1e3, m.median * 1e3, mcpu.best * 1e3, mcpu.median * 1e3,
      o.driver, g.best / m.best, gc.best / mcpu.best, golden.stats.pixels, fragments, psnr, far, mesa.renderer());
  // The machine-readable line scripts/render-vs-llvmpipe reads.
  fmt::print(
      "RESULT scene={} width={} height={} threads={} golden_ms={:.3f} mesa_ms={:.3f} ratio={:.3f} golden_cpu_ms={:.3f} "
      "mesa_cpu_ms={:.3f} cpu_ratio={:.3f} pixels={} fragments={} psnr={:.2f}\n",
      scene.name, scene.width, scene.height, o.threads, g.best * 1e3, m.best * 1e3, g.best / m.best, gc.best * 1e3,
      mcpu.best * 1e3, gc.best / mcpu.best, golden.stats.pixels, fragments, psnr);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const InputError& e) {
    std::fprintf(stderr, "tfu_bench_render_mesa: %s\n", e.what());
    return 2;
  }
}
