// Request traces: the text format that `tfu sample`, the scene renderer and the cycle model share.
// Full description with examples: docs/traces.md.
//
//   # comment lines and blank lines are ignored anywhere
//   # tfu-trace mode=quad [fields=texture,sampler,stage,x,y,s,t]
//                                  optional header fixing the mode (lod | grad | quad) and, with
//                                  fields=, the columns of a request line by name
//   # tfu-texture N SPEC [key=value ...]   binds texture descriptor N (docs/traces.md)
//   # tfu-sampler N key=value ...          binds sampler descriptor N
//   s,t,lod                        mode lod : explicit LOD (GLSL textureLod)
//   s,t,dsdx,dtdx,dsdy,dtdy        mode grad: explicit gradients (GLSL textureGrad)
//   s,t                            mode quad: 4 consecutive lines are the pixels (0,0), (1,0), (0,1),
//                                  (1,1) of a 2x2 quad; the LOD unit derives lambda from them
// Numbers are decimal floating point ([+-]digits[.digits][e[+-]digits], or nan, inf, infinity in
// any case; no hex floats, no stray bytes), read as IEEE binary32 with round-to-nearest (strtof):
// the unit's interface format. Fields are separated by commas with
// optional spaces. Without a header the mode follows from the field count of the first request; every
// line must then have the same count. A trace without texture / sampler columns names descriptor 0
// in every request (old traces read unchanged). A quad trace may carry each quad's screen position
// (columns x and y, both or neither: the top-left pixel of the quad), so that it can be re-ordered
// (reorder_trace). Errors name the file and line.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cmodel/aniso.hpp"
#include "cmodel/enum_names.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/raster_order.hpp"

namespace tfu {

enum class TraceMode { Lod, Grad, Quad };
inline constexpr EnumNames<TraceMode, 3> kTraceModeNames{
    "trace mode", {{{TraceMode::Lod, "lod"}, {TraceMode::Grad, "grad"}, {TraceMode::Quad, "quad"}}}};
const char* trace_mode_name(TraceMode m);

struct TraceRequest {
  uint16_t texture = 0;  // texture descriptor index
  uint8_t sampler = 0;   // sampler descriptor index
  uint8_t stage = 0;     // texture stage of the material that issued it (statistics only)
  uint16_t x = 0, y = 0;  // quad mode, Trace::positions: the screen position of the quad's top-left pixel
  float s = 0, t = 0;
  float lod = 0;                              // mode lod
  float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;  // mode grad
};

// A "# tfu-texture N SPEC key=value..." or "# tfu-sampler N key=value..." header line, as written;
// what the keys mean is docs/traces.md (resolved by cmodel/bindings.hpp).
struct TraceBinding {
  int index = 0;
  std::string spec;                           // textures: file path or proc:NAME[:SIZE]
  std::map<std::string, std::string> params;  // key=value
  std::string where;                          // "file:line" for error messages
};

struct Trace {
  TraceMode mode = TraceMode::Quad;
  std::vector<TraceRequest> requests;  // quad mode: a multiple of 4, in quad order
  bool positions = false;  // the requests carry their quads' screen positions (columns x, y)
  std::vector<TraceBinding> textures, samplers;  // header bindings, in file order
  std::string source;  // the file it was read from (relative texture paths resolve against its directory)
  // The memory budget's charge for `requests` as parse_trace reserved them (cmodel/memory_budget.hpp).
  std::shared_ptr<MemoryCharge> memory;
};

// Throws InputError "<name>:<line>: ..." on malformed input.
Trace parse_trace(std::istream& in, const std::string& name);
// Reads a trace file (cmodel/input_file.hpp: a regular file of at most kMaxTraceBytes).
Trace load_trace(const std::string& path);
// Writes the header line and one line per request; floats printed with 9 significant digits so that
// they read back to the same binary32 value.
void write_trace(std::ostream& out, const Trace& trace);

// lambda (before bias and clamp) of one request (quad mode: of the quad starting at request i; i
// must be a multiple of 4) for a texture whose level 0 is width x height: lod mode -> the explicit
// LOD, grad mode -> the gradients, quad mode -> the quad's coarse derivatives (lod.hpp). The LOD
// unit of both the golden model and the cycle model computes exactly this.
int32_t request_lambda(const Trace& trace, size_t i, int width, int height);
// The texel-space derivatives of one request (quad mode: of the quad starting at request i) for a
// texture whose level 0 is width x height: grad mode -> derivatives_from_gradients, quad mode ->
// derivatives_from_quad (lod.hpp); nullopt in lod mode (textureLod has no derivatives).
std::optional<TexelDerivatives> request_derivatives(const Trace& trace, size_t i, int width, int height);
// The LOD unit's whole result for one request (as request_lambda): aniso_lod of its derivatives
// with the sampler's anisotropy fields `p` (SamplerDescriptor::aniso()); a lod-mode request has no
// derivatives and gets one probe at its explicit lambda (isotropic_lod). With p.max_aniso = 1,
// lambda_q8 is request_lambda's, bit for bit (docs/anisotropic.md).
AnisoLod request_lod(const Trace& trace, size_t i, int width, int height, const AnisoParams& p);
// lambda of every request, in order; `extent(texture index)` gives the texture's level-0 size.
std::vector<int32_t> trace_lambdas(const Trace& trace, const std::function<std::pair<int, int>(int)>& extent);
std::vector<int32_t> trace_lambdas(const Trace& trace, int width, int height);  // every request, one texture

// Largest screen coordinate a trace position may hold (a render is at most 8192 pixels a side).
inline constexpr int kMaxTracePosition = 8191;

// Re-orders a quad trace that carries positions into `order` (cmodel/raster_order.hpp): quads
// grouped by screen tile (row order), inside a tile by their rank in the tile's order (row-major or
// Morton), equal positions keeping the trace's order. A trace records no triangles, so this equals
// the render's order where every triangle covers a quad position once per tile in the trace's own
// order: always for the tile's grouping; within a tile the render draws triangle by triangle, this
// quad position by quad position (docs/traces.md). InputError for a trace without positions.
Trace reorder_trace(const Trace& trace, const RasterOrder& order);

// Largest trace accepted (requests), so that a bad file cannot exhaust memory.
inline constexpr size_t kMaxTraceRequests = size_t{1} << 26;

}  // namespace tfu
