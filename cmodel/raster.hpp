// A small scan-converting renderer that feeds the texture sampler the way a GPU does: in 2x2 pixel
// quads, with lambda from the quad's coarse derivatives (Pharr, GPU Gems ch. 25). Conventions (full
// text in docs/renderer.md):
//   camera        GL conventions: right-handed view space looking down -z, clip z in [-w, w]
//   clipping      in clip space against near, far and a guard band |x|, |y| <= 8 w (Sutherland-Hodgman;
//                 (s, t) and the clip position are interpolated linearly in clip space); the clipped
//                 polygon is fanned from its first vertex
//   viewport      pixel (x, y) covers [x, x+1) x [y, y+1), row 0 on top; its sample point is the centre
//   coverage      integer edge functions on vertices snapped to 1/256 pixel (8 subpixel bits), D3D/GL
//                 top-left fill rule: a centre on an edge belongs to the triangle only if the edge is a
//                 top edge (horizontal, interior below) or a left edge (interior to its right)
//   degenerate    triangles with zero area in world space or after snapping are skipped (counted)
//   culling       Scene::cull: triangles of that on-screen winding (decided on the snapped vertices)
//                 are not drawn (counted); none by default; a depth buffer (z_ndc, less-than)
//                 resolves visibility
//   primary       stage 0 combines with white, or with the vertex colour (Mesh::vertex_colour):
//                 interpolated perspective-correct like (s, t), rounded to 8 bits per channel
//   display       Scene::display_shift: each drawn pixel min(255, v << shift) after the last stage
//   interpolation z affine in screen space; s, t perspective-correct: (sum b_i s_i / w_i) / (sum b_i / w_i)
//                 with barycentrics b_i from the snapped edge functions (helper pixels extrapolate)
//   quads         pixel order (0,0), (1,0), (0,1), (1,1) of a quad at even (x, y); a quad is shaded when
//                 one of its pixels is covered and passes the depth test; all four (s, t) go to
//                 lambda_from_quad, the covered pixels are sampled
//   threads       the image is cut into bands of kBandRows rows; threads take bands in turn; a band
//                 draws triangles in scene order, so the image and the trace do not depend on the
//                 number of threads
//   trace         quad mode, 4 lines per shaded quad with its screen position; in the raster order
//                 (raster_order.hpp); scanline: by band, then triangle, then quad (row-major)
//   ground truth  8 x 8 stratified sample points per pixel at ((i + 1/2) / 8, (j + 1/2) / 8), each with
//                 its own coverage, depth test and perspective-correct (s, t), colour from the texture's
//                 analytic function (procedural.hpp; file textures: bilinear on level 0), averaged
//                 (`truth`, antialiased: its polygon edges are smooth where the render's are not)
//   surface truth the render's own coverage: at each pixel the triangle the render drew at the centre,
//                 its material integrated over the same 8 x 8 points with barycentrics extrapolated
//                 beyond its edges (`surface_truth`; the background where the render drew nothing);
//                 `interior` marks the pixels whose 2x2 quad is drawn by one mesh (docs/metrics.md)
//   sRGB stages   an srgba8 texture is interpolated in linear light in both truths, and a pixel whose
//                 mesh has an srgba8 stage averages its surface-truth samples in linear light (docs/srgb.md)
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "cmodel/golden_unit.hpp"
#include "cmodel/raster_order.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"

namespace tfu {

inline constexpr int kSubpixelBits = 8;       // vertex snapping: 1/256 pixel
inline constexpr int kBandRows = 16;          // rows per band (a multiple of 2: whole quads)
inline constexpr int kTruthSamplesPerAxis = 8;
inline constexpr double kGuardBand = 8.0;     // clip |x|, |y| <= 8 w

// A vertex after the viewport transform: pixel coordinates (y down), depth in [0, 1], 1/w, and
// (s/w, t/w) of each UV set.
struct ScreenVertex {
  double x = 0, y = 0, z = 0;
  double inv_w = 1;
  std::array<glm::dvec2, 2> uv_w{};
  glm::dvec4 colour_w{0.0};  // vertex colour (0..255 per channel) / w
};

// A triangle ready for scan conversion (counter-clockwise on screen after setup, area > 0).
struct RasterTriangle {
  std::array<ScreenVertex, 3> v{};
  std::array<int64_t, 3> X{}, Y{};  // snapped vertex positions, Q.8 pixels
  int64_t area = 0;                 // twice the snapped area, Q.16, > 0
  bool clockwise = false;           // the winding as given was clockwise on screen (y down: area > 0)
  std::array<int64_t, 3> bias{};    // 0 for top-left edges, -1 otherwise (edge i is opposite vertex i)
  int xmin = 0, xmax = -1, ymin = 0, ymax = -1;  // pixel bounding box, clipped to the viewport
  int mesh = 0;

  // Edge function of edge i (from vertex i+1 to vertex i+2) at a Q.8 point.
  int64_t edge(int i, int64_t px, int64_t py) const;
  bool covers_point(int64_t px, int64_t py) const;  // fill rule applied
  bool covers_pixel(int x, int y) const { return covers_point(centre(x), centre(y)); }
  // The pixels of row `row` (in ymin..ymax) whose centres the triangle covers, [first, last] within
  // xmin..xmax (first > last: none): the covered interval solved exactly on the integer edge
  // functions, equal to covers_pixel over the row (Raster.CoveredIntervalEqualsPerPixelCoverage).
  std::pair<int, int> covered_interval(int row) const;
  std::array<double, 3> barycentric(int64_t px, int64_t py) const;
  static constexpr int64_t centre(int x) { return (int64_t{x} << kSubpixelBits) + (1 << (kSubpixelBits - 1)); }
};

// Snaps, orients and sets up a triangle; std::nullopt if its snapped area is zero.
std::optional<RasterTriangle> setup_triangle(const std::array<ScreenVertex, 3>& v, int width, int height);

// A vertex in homogeneous clip space with its attributes, and the clipper of setup: a polygon clipped
// against near, far and the guard band (Sutherland-Hodgman, attributes interpolated linearly in clip
// space); empty if less than a triangle remains. Also the GL replay's (gl_replay.hpp).
struct ClipVertex {
  glm::dvec4 p;
  std::array<glm::dvec2, 2> uv;  // UV sets 0 and 1
  glm::dvec4 colour{255.0};      // vertex colour, 0..255 per channel
};
using Polygon = std::vector<ClipVertex>;
Polygon clip_polygon(Polygon poly);

// Perspective-correct (s, t) of UV set `set` at barycentrics b, and the primary colour (the vertex
// colour interpolated perspective-correct, rounded to 8 bits per channel).
glm::dvec2 interpolate_st(const RasterTriangle& tri, const std::array<double, 3>& b, int set);
Rgba8 primary_colour(const RasterTriangle& tri, const std::array<double, 3>& b);

// GL camera matrices (gluLookAt, gluPerspective).
glm::dmat4 view_matrix(const Camera& cam);
glm::dmat4 projection_matrix(const Camera& cam, double aspect);

class TraceSink;

struct RenderOptions {
  std::optional<FilterMode> filter;  // replaces the filter mode of every mesh's base stage
  Params sampler_overrides;          // further sampler keys of every base stage (bindings.hpp)
  int line_bytes = 64;               // the unit's cache line: textures are tiled in tiles of it
  std::optional<MemoryLayout> texture_layout;  // every texture's layout (SceneOverrides::layout)
  bool trace = false;                // record the quad request trace
  RasterOrder raster;                // the order of the trace's quads (cmodel/raster_order.hpp)
  bool ground_truth = false;         // also render the supersampled analytic references (both truths)
  bool ideal = false;                // Sampler::sample_ideal (double path) instead of sample
  bool keep_coords = false;          // keep each visible pixel's (s, t) (NaN where nothing is drawn)
  int threads = 0;                   // 0: std::thread::hardware_concurrency()
  // With `trace` and the scanline order: the trace goes to this sink band by band instead of into
  // RenderResult::trace and quad_targets (which stay empty).
  TraceSink* sink = nullptr;
};

struct RenderStats {
  int64_t triangles = 0;   // in the scene
  int64_t degenerate = 0;  // skipped: zero area in world space or after snapping
  int64_t clipped_away = 0;  // entirely outside the view volume
  int64_t culled = 0;        // screen triangles not drawn for their winding (Scene::cull)
  int64_t rasterized = 0;  // screen triangles after clipping and setup
  int64_t quads = 0;       // shaded quads (= trace requests / 4)
  int64_t pixels = 0;      // sampled pixels (including overdraw)
};

// Where a traced quad's results go (RenderOptions::trace): the mesh it samples, its top-left pixel,
// the covered pixels that passed the depth test (bit k = pixel k of the quad) and the material
// stage it is. The stages of one shaded quad follow each other; combining their outputs by the
// stages' texture environments (compose_quad_outputs) reproduces the image.
struct QuadTarget {
  int mesh = 0;
  int x = 0, y = 0;
  uint8_t mask = 0;
  uint8_t stage = 0;
  std::array<Rgba8, 4> primary{kPrimaryColour, kPrimaryColour, kPrimaryColour, kPrimaryColour};  // stage 0's Cp
};

// Wall-clock seconds of a render's parts, for speed measurements only (no result depends on them;
// testbench/bench_render_mesa.cpp). upload: the frame's descriptors and texel memory and the golden
// unit's samplers (as a GL driver's texture upload); draw: everything after it, i.e. transform,
// clipping and triangle setup, the colour and depth buffers cleared, every band rasterized and
// shaded on the render's threads, and the bands' outputs (trace, quad targets) gathered in order;
// draw_cpu: the process's CPU seconds over the same span (std::clock: every thread's; on a loaded
// machine the steadier figure); bands_cpu: the CPU seconds of the render's band workers alone
// (each thread's, summed: rasterizing and shading, and with a trace sink the bands handed to it),
// which with a sink (whose consumers run threads of their own) draw_cpu does not separate.
struct RenderTimes {
  double upload = 0, draw = 0, draw_cpu = 0, bands_cpu = 0;
};

// Receives a render's trace in its order, band by band (kBandRows rows; RenderOptions::sink), so
// that a consumer (the streamed scene simulation, rtl/scene_sim.hpp) need not hold the frame's
// trace: begin() once the frame's descriptors and texel memory exist, before any band; then each
// band's requests (4 per quad target) and quad targets, top to bottom, from one thread at a time.
// The render shades at most 2 x threads bands ahead of the last one handed on.
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  virtual void begin(const SceneFrame& frame) = 0;
  virtual void band(const std::vector<TraceRequest>& requests, const std::vector<QuadTarget>& targets) = 0;
};

struct RenderResult {
  Image image;
  Image truth;          // antialiased truth; empty unless RenderOptions::ground_truth
  Image surface_truth;  // the truth with the render's coverage (isolates the filter); likewise
  std::vector<uint8_t> interior;  // per pixel, 1: its quad lies inside one mesh; likewise
  Trace trace;  // empty unless RenderOptions::trace
  std::vector<QuadTarget> quad_targets;  // one per traced quad
  std::shared_ptr<const SceneFrame> frame;  // the descriptors and texel memory the render used
  std::vector<std::array<float, 2>> coords;  // width x height, row-major, if keep_coords
  std::vector<float> depth;  // the depth buffer after the frame: width x height, z of the pixel drawn, +inf where none
  RenderStats stats;
  RenderTimes times;
};

RenderResult render_scene(const Scene& scene, const RenderOptions& opts);
// The same into `result`, whose colour and depth buffers' memory is reused (every field is
// overwritten): a loop drawing frame after frame clears its framebuffer, as a GL driver does,
// instead of allocating it (and taking its page faults) per frame. Results identical to the above.
void render_scene(const Scene& scene, const RenderOptions& opts, RenderResult& result);

// The colour of a pixel the render leaves empty: the scene's background, rounded to 8 bits.
Rgba8 background_rgba8(const Scene& scene);

// Writes the covered pixels of traced quads into `image` from the filtered outputs of their
// requests (4 per quad target, in target order): each quad's stages combined in order by their
// texture environments, as the renderer does, then the display ramp (Scene::display_shift).
void compose_quad_outputs(const Scene& scene, const std::vector<QuadTarget>& targets, const std::vector<Rgba8>& outputs,
                          Image& image);

}  // namespace tfu
