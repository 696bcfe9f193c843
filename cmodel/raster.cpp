#include "cmodel/raster.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <ctime>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"
#include "cmodel/lod_fast.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/raster_quad_avx.hpp"
#include "cmodel/raster_quad_fast.hpp"
#include "cmodel/texenv.hpp"
#include "cmodel/texenv_quad.hpp"

namespace tfu {
namespace {

constexpr int64_t kOne = int64_t{1} << kSubpixelBits;  // one pixel in Q.8
constexpr int kTruthSamples = kTruthSamplesPerAxis * kTruthSamplesPerAxis;
constexpr std::array<Rgba8, 4> kPrimaryQuad{kPrimaryColour, kPrimaryColour, kPrimaryColour, kPrimaryColour};

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// ---- Clipping (Sutherland-Hodgman in homogeneous clip space) ----

// Half-spaces dot(plane, p) >= 0: near, far, then the guard band.
constexpr std::array<glm::dvec4, 6> kClipPlanes{glm::dvec4{0, 0, 1, 1},           glm::dvec4{0, 0, -1, 1},
                                                glm::dvec4{1, 0, 0, kGuardBand},  glm::dvec4{-1, 0, 0, kGuardBand},
                                                glm::dvec4{0, 1, 0, kGuardBand},  glm::dvec4{0, -1, 0, kGuardBand}};

Polygon clip_against(const Polygon& in, const glm::dvec4& plane) {
  Polygon out;
  for (size_t i = 0; i < in.size(); ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % in.size()];
    const double da = glm::dot(plane, a.p), db = glm::dot(plane, b.p);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      const double t = da / (da - db);
      out.push_back({a.p + t * (b.p - a.p),
                     {a.uv[0] + t * (b.uv[0] - a.uv[0]), a.uv[1] + t * (b.uv[1] - a.uv[1])},
                     a.colour + t * (b.colour - a.colour)});
    }
  }
  return out;
}

}  // namespace

Polygon clip_polygon(Polygon poly) {
  for (const glm::dvec4& plane : kClipPlanes) {
    if (poly.empty()) break;
    const bool all_in =
        std::all_of(poly.begin(), poly.end(), [&](const ClipVertex& v) { return glm::dot(plane, v.p) >= 0; });
    if (!all_in) poly = clip_against(poly, plane);
  }
  return poly.size() >= 3 ? poly : Polygon{};
}

namespace {

ScreenVertex to_screen(const ClipVertex& c, int width, int height) {
  const double inv_w = 1.0 / c.p.w;
  ScreenVertex v;
  v.x = (c.p.x * inv_w + 1.0) * 0.5 * width;
  v.y = (1.0 - c.p.y * inv_w) * 0.5 * height;
  v.z = (c.p.z * inv_w + 1.0) * 0.5;
  v.inv_w = inv_w;
  for (size_t k = 0; k < 2; ++k) v.uv_w[k] = c.uv[k] * inv_w;
  v.colour_w = c.colour * inv_w;
  return v;
}

// ---- Per-render shared state ----
struct Context {
  const Scene* scene = nullptr;
  const RenderOptions* opts = nullptr;
  int width = 0, height = 0;
  const SceneFrame* frame = nullptr;
  std::unique_ptr<GoldenUnit> golden;
  std::vector<std::vector<const Sampler*>> samplers;  // per mesh, per stage: the golden unit's sampler
  std::vector<RasterTriangle> triangles;
  std::vector<std::vector<uint32_t>> band_triangles;  // per band: triangle indices in scene order
  RenderResult* result = nullptr;
  std::vector<float> depth;
  Rgba8 background{};           // the colour buffer's clear value (background_rgba8)
  std::vector<int32_t> winner;  // per pixel: the triangle the render drew last there (-1: none), for the surface truth
};

struct BandOutput {
  std::vector<TraceRequest> trace;
  std::vector<QuadTarget> targets;
  std::vector<uint32_t> triangles;  // per target: the triangle that shaded it (raster_sequence)
  int64_t quads = 0, pixels = 0;
};

Rgba8 to_rgba8(const std::array<double, 4>& c) {
  const auto q = [](double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return {q(c[0]), q(c[1]), q(c[2]), q(c[3])};
}

}  // namespace

// Perspective-correct (s, t) of UV set `set` at barycentrics b (Heckbert & Moreton: interpolate
// s/w, t/w and 1/w).
glm::dvec2 interpolate_st(const RasterTriangle& tri, const std::array<double, 3>& b, int set) {
  double inv_w = 0, s_w = 0, t_w = 0;
  for (size_t i = 0; i < 3; ++i) {
    inv_w += b[i] * tri.v[i].inv_w;
    s_w += b[i] * tri.v[i].uv_w[static_cast<size_t>(set)].x;
    t_w += b[i] * tri.v[i].uv_w[static_cast<size_t>(set)].y;
  }
  if (!(inv_w > 0)) {
    // A helper pixel extrapolated beyond the horizon: keep the sign sane, the quad's lambda saturates.
    inv_w = 1e-6 * std::min({tri.v[0].inv_w, tri.v[1].inv_w, tri.v[2].inv_w});
  }
  return {s_w / inv_w, t_w / inv_w};
}

namespace {

// Perspective-correct vertex colour (0..255 per channel) at barycentrics b.
glm::dvec4 interpolate_colour(const RasterTriangle& tri, const std::array<double, 3>& b) {
  double inv_w = 0;
  glm::dvec4 c_w{0.0};
  for (size_t i = 0; i < 3; ++i) {
    inv_w += b[i] * tri.v[i].inv_w;
    c_w += b[i] * tri.v[i].colour_w;
  }
  if (!(inv_w > 0)) inv_w = 1e-6 * std::min({tri.v[0].inv_w, tri.v[1].inv_w, tri.v[2].inv_w});
  return c_w / inv_w;
}

}  // namespace

// The primary colour of a pixel: the interpolated vertex colour rounded to 8 bits per channel.
Rgba8 primary_colour(const RasterTriangle& tri, const std::array<double, 3>& b) {
  const glm::dvec4 c = interpolate_colour(tri, b);
  const auto q = [](double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); };
  return {q(c.r), q(c.g), q(c.b), q(c.a)};
}

namespace {

// The display ramp in real arithmetic (the ideal path's and the truth's).
std::array<double, 4> display_ramp_real(std::array<double, 4> c, int shift) {
  for (size_t i = 0; i < 3; ++i) c[i] = std::min(1.0, c[i] * (1 << shift));
  return c;
}

double interpolate_z(const RasterTriangle& tri, const std::array<double, 3>& b) {
  return b[0] * tri.v[0].z + b[1] * tri.v[1].z + b[2] * tri.v[2].z;
}

float to_float_coord(double v) { return static_cast<float>(std::clamp(v, -1e30, 1e30)); }

// Real-valued texel-space derivatives of the quad (du/dx, dv/dx, du/dy, dv/dy; the ideal path).
std::array<double, 4> ideal_derivatives(const std::array<glm::dvec2, 4>& st, int w, int h) {
  return {(st[1].x - st[0].x) * w, (st[1].y - st[0].y) * h, (st[2].x - st[0].x) * w, (st[2].y - st[0].y) * h};
}

// Real-valued lambda of the quad (for the ideal path): log2 of the longer texel-space derivative.
double ideal_lambda(const std::array<glm::dvec2, 4>& st, int w, int h) {
  const double dudx = (st[1].x - st[0].x) * w, dvdx = (st[1].y - st[0].y) * h;
  const double dudy = (st[2].x - st[0].x) * w, dvdy = (st[2].y - st[0].y) * h;
  const double rho2 = std::max(dudx * dudx + dvdx * dvdx, dudy * dudy + dvdy * dvdy);
  return rho2 > 0 ? 0.5 * std::log2(rho2) : kLodMinusInfinity / 256.0;
}

// Shades the quads of one triangle that lie in rows [y0, y1): per quad, every stage of the mesh's
// material in order (its UV set, lambda from its texture, the golden unit's sampler on the covered
// pixels), combined by the texture environment.
// Bands own disjoint rows, so concurrent calls write disjoint parts of the image and depth buffer.
void shade_triangle(Context& ctx, const RasterTriangle& tri, int y0, int y1, BandOutput& out) {
  const Mesh& mesh = ctx.scene->meshes[static_cast<size_t>(tri.mesh)];
  const auto& samplers = ctx.samplers[static_cast<size_t>(tri.mesh)];
  const auto& bindings = ctx.frame->stages[static_cast<size_t>(tri.mesh)];
  RenderResult& res = *ctx.result;
  const int W = ctx.width, H = ctx.height;
  const int qy_first = std::max(tri.ymin, y0) & ~1, qy_last = std::min(tri.ymax, y1 - 1);
  // The edge functions at the pixel centres, stepped in integers across a row of quads: edge i at
  // (x + 1, y) is edge i at (x, y) minus (Y[b] - Y[a]) one pixel, exactly RasterTriangle::edge of
  // each centre (the same integers; setup bounds them below 2^58). Coverage is decided on them
  // before any barycentric is formed: a quad none of whose centres is covered costs no division.
  std::array<int64_t, 3> step_x{}, step_quad{};
  for (size_t i = 0; i < 3; ++i) step_x[i] = -(tri.Y[(i + 2) % 3] - tri.Y[(i + 1) % 3]) * kOne, step_quad[i] = 2 * step_x[i];
  const auto area = static_cast<double>(tri.area);
  // The fast paths (raster_quad_fast.hpp, texenv_quad.hpp: four pixels at once) or their plain twins.
  const bool fast = fast_paths_enabled();
  const bool avx = fast && raster_avx::available();  // the quad's interpolation four lanes a register (raster_quad_avx.hpp)
  const int display_shift = ctx.scene->display_shift;
  // The options and buffers in locals: the colour stores (bytes) may alias anything, and the
  // compiler would reload them through ctx after each.
  const bool ideal_path = ctx.opts->ideal, trace = ctx.opts->trace, keep_coords = ctx.opts->keep_coords;
  const bool track_winner = !ctx.winner.empty();
  const bool plain_outputs = !ideal_path && !track_winner && !keep_coords;  // each drawn pixel: colour and depth only
  const auto triangle_index = static_cast<int32_t>(&tri - ctx.triangles.data());
  Rgba8* const image = res.image.texels.data();
  float* const depth = ctx.depth.data();
  // Per-quad scratch, zeroed once per call here rather than once per quad (a 128-byte clear per quad
  // cost more than the work it guards): each quad writes what it reads.
  raster_fast::QuadLanes lanes{};                 // the fast path's interpolation
  std::array<std::array<double, 4>, 4> ideal{};   // the ideal path's colours
  std::array<float, 4> s0{}, t0{};                // UV set of stage 0 (kept coordinates)
  // What each stage reads per quad, the same for every quad of the triangle: looked up once here
  // (the first kMaxStages stages; a mesh has no more, scene.cpp).
  struct StageState {
    const TextureStage* stage;
    const Sampler* sampler;
    int width, height, uv_set;
    bool aniso, mip_none;
  };
  const size_t stage_count = mesh.stages.size();
  const auto make_state = [&](size_t st) {
    const Sampler& sampler = *samplers[st];
    return StageState{&mesh.stages[st], &sampler, sampler.texture().width(), sampler.texture().height(), mesh.stages[st].uv_set,
                      sampler.descriptor().anisotropic(), sampler.descriptor().mode.mip == MipMode::None};
  };
  std::array<StageState, kMaxStages> stage_state{};
  for (size_t st = 0; st < std::min(stage_count, stage_state.size()); ++st) stage_state[st] = make_state(st);
  unsigned uv_sets = 0;  // bit u: a stage reads UV set u (the AVX form forms them once per quad)
  for (const TextureStage& stage : mesh.stages) uv_sets |= 1u << stage.uv_set;
  raster_avx::QuadCoords coords{};
  for (int qy = qy_first; qy <= qy_last; qy += 2) {
    // The quads of this row that can hold a covered centre: the union of the covered intervals of
    // its two pixel rows; the quads outside it have no covered centre (what the test below would
    // find) and are not visited.
    int x_lo = tri.xmax + 1, x_hi = tri.xmin - 1;
    for (int row = qy; row <= qy + 1 && row <= tri.ymax; ++row) {
      const auto [lo, hi] = tri.covered_interval(row);
      if (lo <= hi) x_lo = std::min(x_lo, lo), x_hi = std::max(x_hi, hi);
    }
    if (x_lo > x_hi) continue;
    const int qx_first = x_lo & ~1, qx_last = x_hi;
    raster_fast::QuadEdges qe;  // qe.e[i][k]: edge i at pixel k of the quad
    auto& e = qe.e;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
        e[static_cast<size_t>(i)][static_cast<size_t>(k)] =
            tri.edge(i, RasterTriangle::centre(qx_first + (k & 1)), RasterTriangle::centre(qy + (k >> 1)));
    // The image bounds: qx <= xmax < W and qy <= ymax < H, so only the quad's second column or row
    // can lie outside.
    const unsigned rows_in = qy + 1 < H ? 0xFu : 0x3u;
    for (int qx = qx_first; qx <= qx_last; qx += 2) {
      unsigned covered = 0;
      if (fast) {
        if (qx != qx_first) raster_fast::step(qe, step_quad);
        covered = raster_fast::coverage(qe, tri.bias) & (qx + 1 < W ? rows_in : rows_in & 0x5u);
      } else {
        if (qx != qx_first)
          for (size_t i = 0; i < 3; ++i)
            for (auto& v : e[i]) v += 2 * step_x[i];
        for (int k = 0; k < 4; ++k) {
          const int px = qx + (k & 1), py = qy + (k >> 1);
          const auto uk = static_cast<size_t>(k);
          if (px < W && py < H && e[0][uk] + tri.bias[0] >= 0 && e[1][uk] + tri.bias[1] >= 0 && e[2][uk] + tri.bias[2] >= 0)
            covered |= 1u << k;
        }
      }
      if (covered == 0) continue;
      // RasterTriangle::barycentric of each centre (helper pixels extrapolate), then depth.
      std::array<std::array<double, 3>, 4> b;
      std::array<double, 4> z{};
      unsigned mask = 0;
      if (fast) {
        if (avx) {
          raster_avx::barycentrics_depth(qe, area, tri, lanes, z);
        } else {
          raster_fast::barycentrics(qe, area, tri, lanes);
          z = raster_fast::depth(lanes, tri);
        }
        mask = raster_fast::depth_test(covered, z, depth, static_cast<size_t>(qy) * static_cast<size_t>(W) + static_cast<size_t>(qx),
                                       static_cast<size_t>(W), qx + 1 < W && rows_in == 0xFu);
        if (mesh.vertex_colour)
          for (size_t k = 0; k < 4; ++k) b[k] = {lanes.b[0][k], lanes.b[1][k], lanes.b[2][k]};
      }
      for (int k = 0; k < 4 && !fast; ++k) {
        const auto uk = static_cast<size_t>(k);
        b[uk] = {static_cast<double>(e[0][uk]) / area, static_cast<double>(e[1][uk]) / area,
                 static_cast<double>(e[2][uk]) / area};
        if (!(covered >> k & 1u)) continue;
        const int px = qx + (k & 1), py = qy + (k >> 1);
        z[uk] = interpolate_z(tri, b[uk]);
        if (z[uk] < depth[static_cast<size_t>(py) * static_cast<size_t>(W) + static_cast<size_t>(px)])
          mask |= 1u << k;
      }
      if (mask == 0) continue;
      std::array<Rgba8, 4> colour;
      std::memcpy(colour.data(), kPrimaryQuad.data(), sizeof colour);  // one 16-byte copy, not 16 byte stores
      if (mesh.vertex_colour)
        for (size_t k = 0; k < 4; ++k)
          if (mask >> k & 1u) colour[k] = primary_colour(tri, b[k]);
      // Stage 0's primary colour for the trace's quad targets, copied only when a trace is kept (the
      // compiler copied it byte by byte, 50 instructions a quad, whether or not it was used).
      alignas(16) std::array<Rgba8, 4> primary{};
      if (trace) std::memcpy(primary.data(), colour.data(), sizeof primary);
      if (ideal_path)
        for (size_t k = 0; k < 4; ++k)
          ideal[k] = {colour[k].r / 255.0, colour[k].g / 255.0, colour[k].b / 255.0, colour[k].a / 255.0};
      if (avx) raster_avx::st_sets(lanes, tri, uv_sets, coords);
      for (size_t st = 0; st < stage_count; ++st) {
        const StageState ss = st < stage_state.size() ? stage_state[st] : make_state(st);
        const TextureStage& stage = *ss.stage;
        const Sampler& sampler = *ss.sampler;
        float s[4], t[4];
        if (avx) {
          const auto uv = static_cast<size_t>(ss.uv_set);
          std::memcpy(s, coords.s[uv].data(), sizeof s);
          std::memcpy(t, coords.t[uv].data(), sizeof t);
        } else if (fast)
          raster_fast::st(lanes, tri, ss.uv_set, s, t);
        else
          for (size_t k = 0; k < 4; ++k) {
            const glm::dvec2 uv = interpolate_st(tri, b[k], stage.uv_set);
            s[k] = to_float_coord(uv.x);
            t[k] = to_float_coord(uv.y);
          }
        if (st == 0 && keep_coords) std::copy(s, s + 4, s0.begin()), std::copy(t, t + 4, t0.begin());
        const bool aniso = ss.aniso;
        if (ideal_path) {
          // The ideal path sees the same FP32 interface coordinates as the datapath, so that fixed vs
          // ideal isolates the datapath's own quantization; it differs only in exact arithmetic.
          std::array<glm::dvec2, 4> st_if;
          for (size_t k = 0; k < 4; ++k) st_if[k] = {s[k], t[k]};
          const double lambda_ideal = ideal_lambda(st_if, ss.width, ss.height);
          const std::array<double, 4> d = ideal_derivatives(st_if, ss.width, ss.height);
          for (size_t k = 0; k < 4; ++k)
            if (mask >> k & 1u)
              ideal[k] = combine_stage(ideal[k], aniso ? sampler.sample_ideal_aniso(s[k], t[k], d) : sampler.sample_ideal(s[k], t[k], lambda_ideal),
                                       stage.combine);
        } else if (aniso) {
          // Anisotropic: the LOD unit's whole result for the quad (N, lambda, major axis), then the
          // covered pixels' probes.
          const AnisoLod lod = aniso_lod(derivatives_from_quad(s, t, ss.width, ss.height), sampler.descriptor().aniso());
          if (fast) {
            texenv_quad::Quad texel{};  // the pixels not drawn combine with 0, unused
            for (size_t k = 0; k < 4; ++k)
              if (mask >> k & 1u) texel[k] = sampler.sample(s[k], t[k], lod);
            texenv_quad::combine(colour, texel, stage.combine);
          } else {
            for (size_t k = 0; k < 4; ++k)
              if (mask >> k & 1u) colour[k] = combine_stage(colour[k], sampler.sample(s[k], t[k], lod), stage.combine);
          }
        } else {
          // A sampler without MIP-mapping selects level 0 whatever lambda is (select_levels): the fast
          // path then leaves lambda at 0 without the LOD unit, as the cycle model's LOD unit does
          // (rtl/lod_unit.hpp); the plain path forms it (PlainPaths.* compare the two).
          // With the fast paths on, the LOD unit's inline form (lod_fast::lambda_from_quad: no call and
          // no read of the switch per quad; LodFast.LambdaFromQuadEqualsThePlainTwin).
          const int32_t lambda = !fast         ? lambda_from_quad(s, t, ss.width, ss.height)
                                 : ss.mip_none ? 0
                                               : lod_fast::lambda_from_quad(s, t, ss.width, ss.height);
          // The quad's covered pixels go to the filter unit together (its quad interface).
          std::array<SampleRequest, 4> reqs;
          std::array<Rgba8, 4> texel;
          size_t n = 0;
          if (fast)
            n = raster_fast::gather_requests(mask, s, t, lambda, reqs.data());
          else
            for (size_t k = 0; k < 4; ++k)
              if (mask >> k & 1u) reqs[n++] = {s[k], t[k], lambda};
          sampler.sample_batch(reqs.data(), n, texel.data());
          if (fast) {
            // The covered pixels' texels back to their lanes; the others 0, unused.
            if (n < 4) raster_fast::spread_texels(mask, texel);
            texenv_quad::combine(colour, texel, stage.combine);
          } else {
            size_t next = 0;
            for (size_t k = 0; k < 4; ++k)
              if (mask >> k & 1u) colour[k] = combine_stage(colour[k], texel[next++], stage.combine);
          }
        }
        if (trace) {
          out.targets.push_back({tri.mesh, qx, qy, static_cast<uint8_t>(mask), static_cast<uint8_t>(st), primary});
          out.triangles.push_back(static_cast<uint32_t>(triangle_index));
          for (size_t k = 0; k < 4; ++k) {
            TraceRequest r;
            r.texture = static_cast<uint16_t>(bindings[st].texture);
            r.sampler = static_cast<uint8_t>(bindings[st].sampler);
            r.stage = static_cast<uint8_t>(st);
            r.x = static_cast<uint16_t>(qx);
            r.y = static_cast<uint16_t>(qy);
            r.s = s[k];
            r.t = t[k];
            out.trace.push_back(r);
          }
        }
      }
      if (fast && !ideal_path) texenv_quad::display_ramp(colour, display_shift);
      if (fast && plain_outputs) {
        // Only colour and depth kept: two pixels of a row at once (raster_quad_fast.hpp).
        raster_fast::write_quad(mask, colour, z, static_cast<size_t>(qy) * static_cast<size_t>(W) + static_cast<size_t>(qx),
                                static_cast<size_t>(W), image, depth);
      } else {
        for (int k = 0; k < 4; ++k) {
          if (!(mask >> k & 1u)) continue;
          const auto uk = static_cast<size_t>(k);
          const size_t idx = static_cast<size_t>(qy + (k >> 1)) * static_cast<size_t>(W) + static_cast<size_t>(qx + (k & 1));
          image[idx] = ideal_path ? to_rgba8(display_ramp_real(ideal[uk], display_shift))
                       : fast     ? colour[uk]
                                  : display_ramp(colour[uk], display_shift);
          depth[idx] = static_cast<float>(z[uk]);
          if (track_winner) ctx.winner[idx] = triangle_index;
          if (keep_coords) res.coords[idx] = {s0[uk], t0[uk]};
        }
      }
      out.pixels += (mask & 1u) + (mask >> 1 & 1u) + (mask >> 2 & 1u) + (mask >> 3);  // std::popcount is a libgcc call without POPCNT
      ++out.quads;
    }
  }
}

// ---- Ground truth ----

// Continuous counterpart of the wrap modes; returns false for "outside, use the border colour".
bool wrap_continuous(WrapMode m, double& c) {
  switch (m) {
    case WrapMode::Repeat: return true;
    case WrapMode::MirroredRepeat: {
      const double p = c - 2.0 * std::floor(c / 2.0);
      c = p <= 1.0 ? p : 2.0 - p;
      return true;
    }
    case WrapMode::ClampToEdge: c = std::clamp(c, 0.0, std::nextafter(1.0, 0.0)); return true;
    case WrapMode::ClampToBorder: return c >= 0.0 && c < 1.0;
  }
  return true;
}

std::array<double, 4> border_colour(const SamplerDescriptor& cfg) {
  return {cfg.border.r / 255.0, cfg.border.g / 255.0, cfg.border.b / 255.0, cfg.border.a / 255.0};
}

// The first texel index of a truth footprint, floor(x) of a position x in texels, as an integer wrap_index takes.
// wrap_continuous has brought every mode but repeat into [0, 1], so only repeat can be far outside the texture
// (a uv of 1e6 on a texture 4,096 wide is 4e9 texels): it is reduced modulo the size with fmod, which is exact,
// before the integer step, so the texel is the one the unreduced index would wrap to (TFU-S E17: the cast of
// floor(x) to int overflowed). The clamp only bounds what cannot occur (a non-finite position).
int64_t truth_texel_index(WrapMode m, double floor_x, int size) {
  if (!std::isfinite(floor_x)) return 0;
  if (m == WrapMode::Repeat) {
    floor_x = std::fmod(floor_x, size);
    if (floor_x < 0) floor_x += size;
  }
  return static_cast<int64_t>(std::clamp(floor_x, -1.0, static_cast<double>(size)));
}

// File textures have no analytic function: bilinear reconstruction of level 0 in double precision.
// sRGB textures (srgba8, docs/srgb.md) in the truths: texels interpolated in linear light (the
// exact EOTF of the codes) and the colour re-encoded with the exact OETF, as the unit's port carries
// it; a pixel whose mesh has an srgba8 stage averages its samples' R, G, B in linear light too.
double linear_light(double code, TexelFormat f) { return f == TexelFormat::SRGBA8 ? srgb::detail::eotf(code) : code; }
std::array<double, 4> srgb_encoded(std::array<double, 4> c, bool srgb) {
  if (srgb)
    for (size_t i = 0; i < 3; ++i) c[i] = srgb::detail::oetf(std::clamp(c[i], 0.0, 1.0));
  return c;
}
bool has_srgb_stage(const Mesh& mesh) {
  for (const TextureStage& st : mesh.stages)
    if (st.texture && st.texture->format == TexelFormat::SRGBA8) return true;
  return false;
}

std::array<double, 4> bilinear_level0(const Texture& tex, const SamplerDescriptor& cfg, double s, double t) {
  const Image& im = tex.levels.front();
  const double x = s * im.width - 0.5, y = t * im.height - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const double fx = x - fx0, fy = y - fy0;
  const int64_t x0 = truth_texel_index(cfg.wrap_s, fx0, im.width), y0 = truth_texel_index(cfg.wrap_t, fy0, im.height);
  std::array<double, 4> out{};
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy);
      const int i = wrap_index(cfg.wrap_s, x0 + dx, im.width), j = wrap_index(cfg.wrap_t, y0 + dy, im.height);
      const Rgba8 c = (i < 0 || j < 0) ? cfg.border : im.at(i, j);
      out[0] += w * linear_light(c.r / 255.0, tex.format);
      out[1] += w * linear_light(c.g / 255.0, tex.format);
      out[2] += w * linear_light(c.b / 255.0, tex.format);
      out[3] += w * c.a / 255.0;
    }
  return srgb_encoded(out, tex.format == TexelFormat::SRGBA8);
}

std::array<double, 4> truth_colour(const TextureStage& stage, double s, double t) {
  const SamplerDescriptor& cfg = stage.sampler;
  if (!wrap_continuous(cfg.wrap_s, s) || !wrap_continuous(cfg.wrap_t, t)) return border_colour(cfg);
  return stage.truth ? stage.truth(s, t) : bilinear_level0(*stage.texture, cfg, s, t);
}

// Every stage of the material at barycentrics b, combined in real arithmetic.
std::array<double, 4> truth_material(const Mesh& mesh, const RasterTriangle& tri, const std::array<double, 3>& b) {
  std::array<double, 4> c{1, 1, 1, 1};
  if (mesh.vertex_colour) {
    const glm::dvec4 v = interpolate_colour(tri, b);
    for (int i = 0; i < 4; ++i) c[static_cast<size_t>(i)] = std::clamp(v[i] / 255.0, 0.0, 1.0);
  }
  for (const TextureStage& stage : mesh.stages) {
    const glm::dvec2 st = interpolate_st(tri, b, stage.uv_set);
    c = combine_stage(c, truth_colour(stage, st.x, st.y), stage.combine);
  }
  return c;
}

struct TruthSample {
  float depth = std::numeric_limits<float>::infinity();
  std::array<float, 4> c{};
};

void truth_band(const Context& ctx, int band, int y0, int y1) {
  const int W = ctx.width, rows = y1 - y0;
  const Scene& scene = *ctx.scene;
  TruthSample bg;
  for (size_t i = 0; i < 4; ++i) bg.c[i] = static_cast<float>(scene.background[i]);
  std::vector<TruthSample> buf(static_cast<size_t>(rows) * static_cast<size_t>(W) * kTruthSamples, bg);
  constexpr int64_t step = kOne / kTruthSamplesPerAxis;  // sample spacing, Q.8
  for (uint32_t ti : ctx.band_triangles[static_cast<size_t>(band)]) {
    const RasterTriangle& tri = ctx.triangles[ti];
    const Mesh& mesh = scene.meshes[static_cast<size_t>(tri.mesh)];
    for (int py = std::max(tri.ymin, y0); py <= std::min(tri.ymax, y1 - 1); ++py)
      for (int px = tri.xmin; px <= tri.xmax; ++px)
        for (int k = 0; k < kTruthSamples; ++k) {
          const int64_t sx = int64_t{px} * kOne + (k % kTruthSamplesPerAxis) * step + step / 2;
          const int64_t sy = int64_t{py} * kOne + (k / kTruthSamplesPerAxis) * step + step / 2;
          if (!tri.covers_point(sx, sy)) continue;
          const auto b = tri.barycentric(sx, sy);
          const auto z = static_cast<float>(interpolate_z(tri, b));
          TruthSample& smp = buf[(static_cast<size_t>(py - y0) * static_cast<size_t>(W) + static_cast<size_t>(px)) *
                                     kTruthSamples + static_cast<size_t>(k)];
          if (!(z < smp.depth)) continue;
          const auto c = display_ramp_real(truth_material(mesh, tri, b), scene.display_shift);
          smp.depth = z;
          for (size_t i = 0; i < 4; ++i) smp.c[i] = static_cast<float>(c[i]);
        }
  }
  // Resolve: box average of the 64 samples of each pixel. Samples no triangle covers take the
  // background in double precision, counted and multiplied (exact for 64 samples), so that a pixel
  // of background alone rounds to exactly the render's background colour.
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < W; ++x) {
      std::array<double, 4> sum{};
      int background = 0;
      for (int k = 0; k < kTruthSamples; ++k) {
        const TruthSample& smp =
            buf[(static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x)) * kTruthSamples +
                static_cast<size_t>(k)];
        if (smp.depth == std::numeric_limits<float>::infinity()) {
          ++background;
          continue;
        }
        for (size_t i = 0; i < 4; ++i) sum[i] += smp.c[i];
      }
      for (size_t i = 0; i < 4; ++i) sum[i] += background * scene.background[i];
      for (double& v : sum) v /= kTruthSamples;
      ctx.result->truth.at(x, y0 + y) = to_rgba8(sum);
    }
}

// The surface truth of rows [y0, y1): each pixel keeps the render's coverage (the triangle the
// render drew at its centre, after the depth test), and that triangle's material is integrated over
// the whole pixel: the same 8 x 8 sample points, with barycentrics extrapolated beyond the
// triangle's edges as helper pixels are (perspective-correct, every stage combined in real
// arithmetic). A pixel the render left empty is the background. So the truth has the render's
// silhouettes, and what remains between them is the filter's error. Also the interior mask: a
// pixel whose 2x2 quad has all four centres drawn by triangles of one mesh.
void surface_truth_band(const Context& ctx, int y0, int y1) {
  const int W = ctx.width, H = ctx.height;
  const Scene& scene = *ctx.scene;
  constexpr int64_t step = kOne / kTruthSamplesPerAxis;
  const auto at = [W](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(W) + static_cast<size_t>(x); };
  const auto mesh_at = [&](int x, int y) {
    if (x >= W || y >= H) return -1;
    const int32_t t = ctx.winner[at(x, y)];
    return t < 0 ? -1 : ctx.triangles[static_cast<size_t>(t)].mesh;
  };
  for (int py = y0; py < y1; ++py)
    for (int px = 0; px < W; ++px) {
      const int32_t ti = ctx.winner[at(px, py)];
      if (ti < 0) {
        ctx.result->surface_truth.at(px, py) = to_rgba8(scene.background);
        continue;
      }
      const RasterTriangle& tri = ctx.triangles[static_cast<size_t>(ti)];
      const Mesh& mesh = scene.meshes[static_cast<size_t>(tri.mesh)];
      const bool srgb = has_srgb_stage(mesh);
      std::array<double, 4> sum{};
      for (int k = 0; k < kTruthSamples; ++k) {
        const int64_t sx = int64_t{px} * kOne + (k % kTruthSamplesPerAxis) * step + step / 2;
        const int64_t sy = int64_t{py} * kOne + (k / kTruthSamplesPerAxis) * step + step / 2;
        const auto c = display_ramp_real(truth_material(mesh, tri, tri.barycentric(sx, sy)), scene.display_shift);
        for (size_t i = 0; i < 4; ++i) {
          const auto v = static_cast<double>(static_cast<float>(c[i]));
          sum[i] += srgb && i < 3 ? srgb::detail::eotf(std::clamp(v, 0.0, 1.0)) : v;
        }
      }
      for (double& v : sum) v /= kTruthSamples;
      ctx.result->surface_truth.at(px, py) = to_rgba8(srgb_encoded(sum, srgb));
      const int qx = px & ~1, qy = py & ~1, m = tri.mesh;
      ctx.result->interior[at(px, py)] =
          mesh_at(qx, qy) == m && mesh_at(qx + 1, qy) == m && mesh_at(qx, qy + 1) == m && mesh_at(qx + 1, qy + 1) == m;
    }
}

// ---- Setup: transform, clip, project, snap, bin into bands ----
void setup_scene(Context& ctx) {
  const Scene& scene = *ctx.scene;
  RenderStats& st = ctx.result->stats;
  const glm::dmat4 mvp = projection_matrix(scene.camera, static_cast<double>(ctx.width) / ctx.height) *
                         view_matrix(scene.camera);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (const auto& tri : mesh.triangles) {
      ++st.triangles;
      const Vertex& a = mesh.vertices.at(tri[0]);
      const Vertex& b = mesh.vertices.at(tri[1]);
      const Vertex& c = mesh.vertices.at(tri[2]);
      if (glm::length(glm::cross(b.pos - a.pos, c.pos - a.pos)) == 0.0) {
        ++st.degenerate;
        continue;
      }
      Polygon poly;
      for (const Vertex* v : {&a, &b, &c})
        poly.push_back({mvp * glm::dvec4(v->pos, 1.0),
                        {v->uv, v->uv1},
                        glm::dvec4(v->colour.r, v->colour.g, v->colour.b, v->colour.a)});
      poly = clip_polygon(std::move(poly));
      if (poly.empty()) {
        ++st.clipped_away;
        continue;
      }
      // Fan from the first vertex of the clipped polygon.
      for (size_t i = 1; i + 1 < poly.size(); ++i) {
        auto rt = setup_triangle({to_screen(poly[0], ctx.width, ctx.height), to_screen(poly[i], ctx.width, ctx.height),
                                  to_screen(poly[i + 1], ctx.width, ctx.height)},
                                 ctx.width, ctx.height);
        if (!rt) {
          ++st.degenerate;
          continue;
        }
        if ((scene.cull == CullWinding::Clockwise && rt->clockwise) ||
            (scene.cull == CullWinding::CounterClockwise && !rt->clockwise)) {
          ++st.culled;
          continue;
        }
        if (rt->xmin > rt->xmax || rt->ymin > rt->ymax) continue;  // off screen inside the guard band
        rt->mesh = static_cast<int>(m);
        ctx.triangles.push_back(*rt);
      }
    }
  }
  st.rasterized = static_cast<int64_t>(ctx.triangles.size());
  const int bands = (ctx.height + kBandRows - 1) / kBandRows;
  ctx.band_triangles.assign(static_cast<size_t>(bands), {});
  for (size_t i = 0; i < ctx.triangles.size(); ++i) {
    const RasterTriangle& t = ctx.triangles[i];
    for (int band = t.ymin / kBandRows; band <= t.ymax / kBandRows; ++band)
      ctx.band_triangles[static_cast<size_t>(band)].push_back(static_cast<uint32_t>(i));
  }
}

// The frame (descriptors, texel memory) and the golden unit's sampler of every stage.
void make_samplers(Context& ctx, RenderResult& result) {
  SceneOverrides ov;
  ov.filter = ctx.opts->filter;
  ov.sampler = ctx.opts->sampler_overrides;
  ov.layout = ctx.opts->texture_layout;
  result.frame = std::make_shared<const SceneFrame>(build_scene_frame(*ctx.scene, ov, ctx.opts->line_bytes));
  ctx.frame = result.frame.get();
  ctx.golden = std::make_unique<GoldenUnit>(ctx.frame->frame);
  for (const auto& mesh : ctx.frame->stages) {
    ctx.samplers.emplace_back();
    for (const StageBinding& b : mesh) ctx.samplers.back().push_back(&ctx.golden->sampler(b.texture, b.sampler));
  }
}

// The colour and depth buffers' rows [y0, y1) cleared (background colour, depth +infinity) by the
// worker about to shade them: every row is one band's, so the frame is cleared as a whole, but in
// parallel and a band at a time, its rows still in the core's cache when the band's quads test and
// write them (a 1080p frame's buffers are 16 MB: cleared in one pass before the bands, they reached
// the bands from memory).
void clear_band(Context& ctx, int y0, int y1) {
  const auto first = static_cast<ptrdiff_t>(y0) * ctx.width, last = static_cast<ptrdiff_t>(y1) * ctx.width;
  std::fill(ctx.result->image.texels.begin() + first, ctx.result->image.texels.begin() + last, ctx.background);
  std::fill(ctx.depth.begin() + first, ctx.depth.begin() + last, std::numeric_limits<float>::infinity());
}

// Runs every band on `threads` workers; bands are independent (disjoint rows). With a trace sink
// (RenderOptions::sink) each band's trace is handed on once it and every band above it are done,
// in band order, by whichever worker completes that run of bands; a worker starts a band only when
// fewer than 2 x threads bands lie between it and the next one to hand on. A band handed on leaves
// its emptied buffers (their capacity) to a band about to start, so no more buffers exist than
// bands in flight (2 x threads), and a band grows into memory already touched instead of fresh
// pages, each a page fault (a 720p band's trace is ~2 MB, 500 pages).
void run_bands(Context& ctx, int threads, std::vector<BandOutput>& outputs) {
  const int bands = static_cast<int>(ctx.band_triangles.size());
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  TraceSink* const sink = ctx.opts->sink;
  const int lookahead = 2 * threads;
  std::mutex emit_mutex;
  std::condition_variable emit_cv;
  int emitted = 0;  // bands handed on
  bool emitting = false, failed = false;
  std::vector<uint8_t> done(static_cast<size_t>(bands), 0);
  std::vector<BandOutput> spare;  // emptied buffers of bands handed on (guarded by emit_mutex)
  const auto fail = [&](std::exception_ptr e) {
    {
      const std::lock_guard lock(error_mutex);
      if (!error) error = e;
    }
    const std::lock_guard lock(emit_mutex);
    failed = true;
    emit_cv.notify_all();
  };
  const auto hand_on = [&](int band) {
    std::unique_lock lock(emit_mutex);
    done[static_cast<size_t>(band)] = 1;
    if (emitting) return;  // the worker handing on picks it up
    emitting = true;
    while (!failed && emitted < bands && done[static_cast<size_t>(emitted)]) {
      BandOutput& b = outputs[static_cast<size_t>(emitted)];
      lock.unlock();
      try {
        sink->band(b.trace, b.targets);
      } catch (...) {
        fail(std::current_exception());
      }
      BandOutput emptied;
      emptied.trace.swap(b.trace);
      emptied.targets.swap(b.targets);
      emptied.triangles.swap(b.triangles);
      emptied.trace.clear();
      emptied.targets.clear();
      emptied.triangles.clear();
      lock.lock();
      spare.push_back(std::move(emptied));
      ++emitted;
      emit_cv.notify_all();
    }
    emitting = false;
  };
  const auto worker = [&] {
    for (int band = next++; band < bands; band = next++) {
      if (sink != nullptr) {
        std::unique_lock lock(emit_mutex);
        emit_cv.wait(lock, [&] { return failed || band < emitted + lookahead; });
        if (failed) return;
        if (!spare.empty()) {
          BandOutput& b = outputs[static_cast<size_t>(band)];
          b.trace.swap(spare.back().trace);
          b.targets.swap(spare.back().targets);
          b.triangles.swap(spare.back().triangles);
          spare.pop_back();
        }
      }
      try {
        const int y0 = band * kBandRows, y1 = std::min(ctx.height, y0 + kBandRows);
        clear_band(ctx, y0, y1);
        for (uint32_t ti : ctx.band_triangles[static_cast<size_t>(band)])
          shade_triangle(ctx, ctx.triangles[ti], y0, y1, outputs[static_cast<size_t>(band)]);
        if (ctx.opts->ground_truth) {
          truth_band(ctx, band, y0, y1);
          surface_truth_band(ctx, y0, y1);
        }
      } catch (...) {
        fail(std::current_exception());
        return;
      }
      if (sink != nullptr) hand_on(band);
    }
  };
  std::mutex cpu_mutex;
  run_workers(threads, [&](int) {
    const double t0 = thread_cpu_seconds();
    worker();
    const double t = thread_cpu_seconds() - t0;
    const std::lock_guard lock(cpu_mutex);
    ctx.result->times.bands_cpu += t;
  });
  if (error) std::rethrow_exception(error);
}

}  // namespace

// ---- RasterTriangle ----

int64_t RasterTriangle::edge(int i, int64_t px, int64_t py) const {
  const auto a = static_cast<size_t>((i + 1) % 3), b = static_cast<size_t>((i + 2) % 3);
  return (X[b] - X[a]) * (py - Y[a]) - (Y[b] - Y[a]) * (px - X[a]);
}

bool RasterTriangle::covers_point(int64_t px, int64_t py) const {
  for (int i = 0; i < 3; ++i)
    if (edge(i, px, py) + bias[static_cast<size_t>(i)] < 0) return false;
  return true;
}

std::pair<int, int> RasterTriangle::covered_interval(int row) const {
  // Along the row, edge i at pixel x is e(x) = e(xmin) + (x - xmin) step with step = -(Y[b] - Y[a])
  // one pixel (Q.8), and the centre is covered where e(x) + bias >= 0 for all three edges.
  int64_t lo = xmin, hi = xmax;
  for (size_t i = 0; i < 3; ++i) {
    const int64_t step = -(Y[(i + 2) % 3] - Y[(i + 1) % 3]) * kOne;
    const int64_t at = edge(static_cast<int>(i), centre(xmin), centre(row)) + bias[i];
    if (step > 0)
      lo = std::max(lo, xmin - floor_div(at, step));  // x - xmin >= ceil(-at / step)
    else if (step < 0)
      hi = std::min(hi, xmin + floor_div(at, -step));  // x - xmin <= floor(at / -step)
    else if (at < 0)
      return {xmin, xmin - 1};  // a horizontal edge the row lies outside of
  }
  if (lo > hi) return {xmin, xmin - 1};
  return {static_cast<int>(lo), static_cast<int>(hi)};
}

std::array<double, 3> RasterTriangle::barycentric(int64_t px, int64_t py) const {
  const auto a = static_cast<double>(area);
  return {static_cast<double>(edge(0, px, py)) / a, static_cast<double>(edge(1, px, py)) / a,
          static_cast<double>(edge(2, px, py)) / a};
}

namespace {

// Largest screen coordinate (pixels) setup accepts: Q.8 positions then fit 29 bits with sign, so
// every edge-function product (two differences of < 2^29) stays below 2^58 and no int64 sum
// overflows. Clipping against the guard band keeps real triangles within a few screen widths; a
// vertex beyond this (or not finite) comes only from absurd input and the triangle is skipped as
// degenerate.
constexpr double kMaxScreenCoord = double{1 << 20};

bool screen_position_ok(const ScreenVertex& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::fabs(v.x) <= kMaxScreenCoord &&
         std::fabs(v.y) <= kMaxScreenCoord;
}

}  // namespace

std::optional<RasterTriangle> setup_triangle(const std::array<ScreenVertex, 3>& v, int width, int height) {
  for (const ScreenVertex& sv : v)
    if (!screen_position_ok(sv)) return std::nullopt;
  RasterTriangle t;
  t.v = v;
  for (size_t i = 0; i < 3; ++i) {
    t.X[i] = std::llround(v[i].x * static_cast<double>(kOne));
    t.Y[i] = std::llround(v[i].y * static_cast<double>(kOne));
  }
  t.area = (t.X[1] - t.X[0]) * (t.Y[2] - t.Y[0]) - (t.Y[1] - t.Y[0]) * (t.X[2] - t.X[0]);
  if (t.area == 0) return std::nullopt;
  t.clockwise = t.area > 0;  // y down: a positive area turns clockwise as seen on the screen
  if (t.area < 0) {          // flip to the orientation the edge functions expect
    std::swap(t.v[1], t.v[2]);
    std::swap(t.X[1], t.X[2]);
    std::swap(t.Y[1], t.Y[2]);
    t.area = -t.area;
  }
  // Top-left rule (y down): edge a->b is top if horizontal with dx > 0, left if dy < 0.
  for (size_t i = 0; i < 3; ++i) {
    const size_t a = (i + 1) % 3, b = (i + 2) % 3;
    const int64_t dx = t.X[b] - t.X[a], dy = t.Y[b] - t.Y[a];
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    t.bias[i] = top_left ? 0 : -1;
  }
  // Pixel bounding box (conservative: every pixel any sample of which may be covered).
  const auto [xlo, xhi] = std::minmax({t.X[0], t.X[1], t.X[2]});
  const auto [ylo, yhi] = std::minmax({t.Y[0], t.Y[1], t.Y[2]});
  t.xmin = static_cast<int>(std::max<int64_t>(0, floor_div(xlo, kOne)));
  t.xmax = static_cast<int>(std::min<int64_t>(width - 1, floor_div(xhi, kOne)));
  t.ymin = static_cast<int>(std::max<int64_t>(0, floor_div(ylo, kOne)));
  t.ymax = static_cast<int>(std::min<int64_t>(height - 1, floor_div(yhi, kOne)));
  return t;
}

glm::dmat4 view_matrix(const Camera& cam) { return glm::lookAt(cam.position, cam.look_at, cam.up); }

glm::dmat4 projection_matrix(const Camera& cam, double aspect) {
  return glm::perspective(glm::radians(cam.fov_y_deg), aspect, cam.near_plane, cam.far_plane);
}

RenderResult render_scene(const Scene& scene, const RenderOptions& opts) {
  RenderResult result;
  render_scene(scene, opts, result);
  return result;
}

void render_scene(const Scene& scene, const RenderOptions& opts, RenderResult& reuse) {
  if (scene.width < 1 || scene.height < 1 || scene.width > kMaxRenderSize || scene.height > kMaxRenderSize)
    throw InputError("render size " + std::to_string(scene.width) + "x" + std::to_string(scene.height) +
                     " outside 1.." + std::to_string(kMaxRenderSize));
  // The colour and depth buffers' memory is kept from the previous frame (cleared band by band,
  // clear_band; no page faults); everything else starts afresh, the previous frame's released at
  // the end (as when the caller's old result outlives the new render).
  std::vector<Rgba8> colour_memory = std::move(reuse.image.texels);
  std::vector<float> depth_memory = std::move(reuse.depth);
  RenderResult result;
  Context ctx;
  ctx.scene = &scene;
  ctx.opts = &opts;
  ctx.width = scene.width;
  ctx.height = scene.height;
  ctx.result = &result;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t_upload = Clock::now();
  make_samplers(ctx, result);
  result.times.upload = seconds_since(t_upload);
  const Clock::time_point t_draw = Clock::now();
  const std::clock_t cpu_draw = std::clock();
  setup_scene(ctx);
  if (opts.sink != nullptr) {
    if (!opts.trace || opts.raster.traversal != RasterTraversal::Scanline)
      throw CheckFailed("a render's trace sink needs the trace in the scanline order");
    opts.sink->begin(*result.frame);
  }

  const size_t n = static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height);
  result.image.width = scene.width;
  result.image.height = scene.height;
  result.image.texels = std::move(colour_memory);
  result.image.texels.resize(n);  // its values: each band's worker clears its rows (clear_band)
  ctx.background = background_rgba8(scene);
  if (opts.ground_truth) {
    result.truth = Image(scene.width, scene.height);
    result.surface_truth = Image(scene.width, scene.height);
    result.interior.assign(static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height), 0);
    ctx.winner.assign(static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height), -1);
  }
  if (opts.keep_coords) result.coords.assign(n, {std::nanf(""), std::nanf("")});
  ctx.depth = std::move(depth_memory);
  ctx.depth.resize(n);  // as the colour buffer: clear_band

  const int bands = static_cast<int>(ctx.band_triangles.size());
  if (opts.threads < 0 || opts.threads > kMaxThreads)
    throw InputError("render threads " + std::to_string(opts.threads) + " outside 0.." + std::to_string(kMaxThreads));
  int threads = opts.threads > 0 ? opts.threads : hardware_threads();
  threads = std::clamp(threads, 1, std::max(1, bands));
  std::vector<BandOutput> outputs(static_cast<size_t>(bands));
  run_bands(ctx, threads, outputs);

  result.trace.mode = TraceMode::Quad;
  result.trace.positions = opts.trace;
  std::vector<QuadPlace> places;
  for (BandOutput& b : outputs) {
    result.stats.quads += b.quads;
    result.stats.pixels += b.pixels;
    result.trace.requests.insert(result.trace.requests.end(), b.trace.begin(), b.trace.end());
    result.quad_targets.insert(result.quad_targets.end(), b.targets.begin(), b.targets.end());
    if (opts.raster.traversal != RasterTraversal::Scanline)
      for (size_t i = 0; i < b.targets.size(); ++i) places.push_back({b.triangles[i], b.targets[i].x, b.targets[i].y});
  }
  if (opts.raster.traversal != RasterTraversal::Scanline) {
    // The bands recorded the quads in scanline order; the same quads, masks and outputs in the
    // raster order (every order shades the same quads: raster_order.hpp).
    const std::vector<size_t> seq = raster_sequence(opts.raster, places);
    std::vector<TraceRequest> requests(result.trace.requests.size());
    std::vector<QuadTarget> targets(result.quad_targets.size());
    for (size_t i = 0; i < seq.size(); ++i) {
      targets[i] = result.quad_targets[seq[i]];
      std::copy_n(result.trace.requests.begin() + static_cast<ptrdiff_t>(seq[i] * 4), 4, requests.begin() + static_cast<ptrdiff_t>(i * 4));
    }
    result.trace.requests = std::move(requests);
    result.quad_targets = std::move(targets);
  }
  result.depth = std::move(ctx.depth);
  result.times.draw = seconds_since(t_draw);
  result.times.draw_cpu = static_cast<double>(std::clock() - cpu_draw) / CLOCKS_PER_SEC;
  reuse = std::move(result);
}

Rgba8 background_rgba8(const Scene& scene) { return to_rgba8(scene.background); }

void compose_quad_outputs(const Scene& scene, const std::vector<QuadTarget>& targets, const std::vector<Rgba8>& outputs,
                          Image& image) {
  std::array<Rgba8, 4> colour{};
  for (size_t q = 0; q < targets.size(); ++q) {
    const QuadTarget& t = targets[q];
    const Mesh& mesh = scene.meshes.at(static_cast<size_t>(t.mesh));
    if (t.stage == 0) colour = t.primary;
    for (size_t k = 0; k < 4; ++k) colour[k] = combine_stage(colour[k], outputs[q * 4 + k], mesh.stages[t.stage].combine);
    if (t.stage + 1u != mesh.stages.size()) continue;
    for (int k = 0; k < 4; ++k)
      if ((t.mask >> k) & 1u)
        image.at(t.x + (k & 1), t.y + (k >> 1)) = display_ramp(colour[static_cast<size_t>(k)], scene.display_shift);
  }
}

}  // namespace tfu
