// Request traces: the text format that `tfu sample`, the scene renderer and the cycle model share.
// Full description with examples: docs/traces.md.
//
//   # comment lines and blank lines are ignored anywhere
//   # tfu-trace mode=quad          optional header fixing the mode (lod | grad | quad)
//   s,t,lod                        mode lod : explicit LOD (GLSL textureLod)
//   s,t,dsdx,dtdx,dsdy,dtdy        mode grad: explicit gradients (GLSL textureGrad)
//   s,t                            mode quad: 4 consecutive lines are the pixels (0,0), (1,0), (0,1),
//                                  (1,1) of a 2x2 quad; the LOD unit derives lambda from them
// Numbers are decimal floating point ([+-]digits[.digits][e[+-]digits], or nan, inf, infinity in
// any case; no hex floats, no stray bytes), read as IEEE binary32 with round-to-nearest (strtof):
// the unit's interface format. Fields are separated by commas with
// optional spaces. Without a header the mode follows from the field count of the first request; every
// line must then have the same count. Errors name the file and line.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace tfu {

enum class TraceMode { Lod, Grad, Quad };
const char* trace_mode_name(TraceMode m);

struct TraceRequest {
  float s = 0, t = 0;
  float lod = 0;                              // mode lod
  float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;  // mode grad
};

struct Trace {
  TraceMode mode = TraceMode::Quad;
  std::vector<TraceRequest> requests;  // quad mode: a multiple of 4, in quad order
};

// Throws InputError "<name>:<line>: ..." on malformed input.
Trace parse_trace(std::istream& in, const std::string& name);
// Reads a trace file (cmodel/input_file.hpp: a regular file of at most kMaxTraceBytes).
Trace load_trace(const std::string& path);
// Writes the header line and one line per request; floats printed with 9 significant digits so that
// they read back to the same binary32 value.
void write_trace(std::ostream& out, const Trace& trace);

// lambda (before bias and clamp) of every request, in order, for a texture whose level 0 is
// width x height: lod mode -> the explicit LOD, grad mode -> the gradients, quad mode -> one lambda
// per quad from its coarse derivatives (lod.hpp). The LOD unit of both the golden model and the
// cycle model computes exactly this.
std::vector<int32_t> trace_lambdas(const Trace& trace, int width, int height);

// Largest trace accepted (requests), so that a bad file cannot exhaust memory.
inline constexpr size_t kMaxTraceRequests = size_t{1} << 26;

}  // namespace tfu
