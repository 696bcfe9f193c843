// The replay of one frame of a game's OpenGL command stream (gl_trace.hpp) as the texture unit's
// workload: the fixed-function GL 1.x subset ioquake3's opengl1 renderer uses, executed call by call
// (docs/gl-replay.md lists what is executed, what is accepted without effect, and what is refused).
//
//   state     texture objects (every uploaded level, filters, wraps, anisotropy), two texture units
//             (binding, enable, environment; client texture coordinate arrays), vertex and colour
//             arrays and the locked range, the current colour and texture coordinates, modelview
//             and projection matrices, viewport, scissor, depth test / function / mask / range,
//             polygon offset, cull face, front face, alpha test, blending, clear values
//   setup     vertices through projection x modelview into clip space, clipped and snapped as the
//             scene renderer does (raster.hpp: clip_polygon, setup_triangle), then the GL viewport
//             (y up: screen row 0 is the framebuffer's top row) and depth range; culling by the GL
//             winding (front: counter-clockwise in window coordinates)
//   quads     each triangle of each draw in call order, its 2x2 quads row-major over its bounding
//             box; a pixel is covered by the fill rule, inside viewport and scissor, and passes the
//             depth test against the depth buffer as previous quads left it (24-bit, window depth
//             plus polygon offset factor * max(|dz/dx|, |dz/dy|) + units / (2^24 - 1), rounded)
//   requests  per enabled unit (unit 0 first): 4 requests of the quad (stage = unit) with the unit's
//             texture and sampler descriptor; both models derive lambda from the quad (lod.hpp)
//   renderer  after the unit, per covered pixel: the texture environments in unit order
//             (texenv.hpp combine_stage; REPLACE of an RGB texture keeps the fragment's alpha), alpha
//             test (8-bit alpha against the reference rounded to 8 bits), depth write, blending on 8-bit
//             codes (one rounding: (S sf + D df + 127) / 255, clamped; destination alpha 1.0 when the
//             visual has no alpha bits), colour write
// The frame starts from a black colour buffer and a depth buffer of 1.0 (earlier frames are not drawn).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cmodel/frame.hpp"
#include "cmodel/texenv.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/trace.hpp"

namespace tfu::gl {

enum class Compare : uint8_t { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };
enum class BlendFactor : uint8_t {
  Zero, One, SrcColour, OneMinusSrcColour, DstColour, OneMinusDstColour,
  SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha, SrcAlphaSaturate
};

// What the renderer does with one draw's fragments after the unit.
struct StageEnv {
  StageCombine combine;
  bool keep_fragment_alpha = false;  // REPLACE of a texture without alpha (internal format RGB)
};
struct DrawOps {
  uint64_t call = 0;             // the draw's call number
  std::vector<StageEnv> stages;  // one per enabled texture unit, in unit order
  bool alpha_test = false;
  Compare alpha_func = Compare::Always;
  uint8_t alpha_ref = 0;
  bool depth_test = false;
  Compare depth_func = Compare::Less;
  bool depth_write = true;
  bool blend = false;
  BlendFactor src = BlendFactor::One, dst = BlendFactor::Zero;
};

// One shaded quad (at least one pixel covered and passing the depth test), in draw order. Its
// requests are 4 per stage from `first_request` (pixel k at (x + (k & 1), y + (k >> 1))).
struct FragmentQuad {
  uint32_t draw = 0;  // index into Replay::draws
  uint16_t x = 0, y = 0;
  uint8_t mask = 0;
  std::array<uint32_t, 4> depth{};  // window depth, 24 bits
  std::array<Rgba8, 4> primary{};
  uint32_t first_request = 0;
};

// A glClear in the frame, before draw `before_draw`: the pixel rectangle [x0, x1) x [y0, y1)
// (the scissor box when the scissor test is on) set to the clear colour and/or depth.
struct ClearOp {
  uint32_t before_draw = 0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool colour = false, depth = false;
  Rgba8 colour_value{};
  uint32_t depth_value = 0;
};

// What the engine's GL state says about one draw, beyond what the renderer needs: the facts a
// script classifies the draw by (the engine's shader stage: base, light map, 2D ...; scripts/game-frames).
struct DrawFacts {
  std::vector<uint32_t> gl_textures;     // per stage: the GL texture object's name
  std::vector<std::string> min_filters;  // per stage: GL_TEXTURE_MIN_FILTER as traced
  double depth_near = 0, depth_far = 1;  // glDepthRange
  bool orthographic = false;             // the projection's last row is (0, 0, 0, 1): glOrtho, the engine's 2D
  uint32_t modelview = 0;                // index of the draw's modelview among the frame's distinct ones, by first use
  int locked_pass = -1;    // draws since glLockArraysEXT before this one (0: the first), -1: arrays not locked
  uint64_t triangles = 0;  // triangles rasterized (after clipping, culling and degenerate ones)
};

struct ReplayStats {
  uint64_t calls = 0, frame_calls = 0;  // calls read; of them in the frame
  uint64_t draws = 0, triangles = 0, culled = 0, clipped_away = 0, degenerate = 0, rasterized = 0;
  uint64_t quads = 0, pixels = 0, textures = 0, samplers = 0;
  uint64_t locked_draws = 0;  // draws inside glLockArraysEXT / glUnlockArraysEXT
};

// Where the replay's time went (thread CPU seconds, but the dump: see gl::Stream):
//   dump_wall, dump_cpu  apitrace dump (its own process: wall clock, CPU)
//   parse                the dump's text parsed
//   state                every call executed: GL state, texture uploads, draws set up (transform, clip, snap)
//   place                the frame's textures placed in the unit's texel memory (FrameBuilder::finish)
//   raster               quads rasterized and depth-tested, their requests made and sampled by the golden
//                        model, the renderer's fragment operations after it
struct ReplayTimes {
  double dump_wall = 0, dump_cpu = 0, parse = 0, state = 0, place = 0, raster = 0;
};

struct Replay {
  std::string trace;
  int frame = 0;
  uint64_t first_call = 0, last_call = 0;  // the frame's calls (the last: its glXSwapBuffers, glretrace's snapshot name)
  int width = 0, height = 0;
  bool destination_alpha = false;  // the visual has alpha bits (else DST_ALPHA reads 1.0)
  std::shared_ptr<const Frame> unit_frame;  // descriptors and texel memory of every texture the frame samples
  Trace requests;                           // quad mode, the unit's workload in issue order
  std::vector<DrawOps> draws;
  std::vector<DrawFacts> facts;  // one per draw
  std::vector<ClearOp> clears;  // in order
  std::vector<FragmentQuad> quads;
  Image image;  // the frame from the golden model's outputs
  ReplayStats stats;
  ReplayTimes times;
};

struct ReplayOptions {
  int line_bytes = 64;  // textures tiled for the unit's cache line
  // The framebuffer's alpha bits: -1 as the trace's visual asks (glXChooseVisual / glXChooseFBConfig:
  // GLX_ALPHA_SIZE), 0 (DST_ALPHA reads 1.0) or 8. glretrace draws into a visual of its own.
  int alpha_bits = -1;
  // The sampler of every mipmapped texture object overridden, as the engine's r_textureMode and
  // r_ext_max_anisotropy set every mipmapped image (textures without MIP levels keep theirs):
  // `min_filter` a GL_*_MIPMAP_* minification filter (its base filter also magnifies), empty: as
  // traced; `max_aniso` 1..16, 0: as traced.
  std::string min_filter;
  int max_aniso = 0;
};

// Reads the trace through `apitrace dump` (gl_trace.hpp) and replays frame `frame` through the golden
// model. InputError naming the trace and call: bad input, or "unsupported GL calls or states: ..."
// listing every unsupported call or state met (by name, with its first call number) in one line.
Replay replay_frame(const std::string& trace, int frame, const ReplayOptions& opts = {});

// The frame composed from the outputs of every request (Replay::requests order): the renderer's
// fragment operations re-run in draw order. With the golden model's outputs it is Replay::image.
Image compose_frame(const Replay& r, const std::vector<Rgba8>& outputs);

// One CSV row per draw (a header line first): the draw's call, its facts (DrawFacts), its fragment
// state and what it costs the unit (quads, covered pixels, requests).
void write_draw_table(const Replay& r, std::ostream& os);

}  // namespace tfu::gl
