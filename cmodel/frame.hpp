// The driver's side of a frame: it places every texture of the frame in one texel memory, fills the
// texture and sampler descriptor tables, and makes the B-spline coefficient textures that
// bspline-interp samplers read. Both models then work from the result: the cycle model from the
// registers and the memory, the golden model (golden_unit.hpp) from the registers and the textures'
// levels (which equal the memory's contents: read_texture(memory, descriptor), tested).
#pragma once

#include <map>
#include <optional>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/texture_memory.hpp"
#include "cmodel/trace.hpp"

namespace tfu {

struct FrameTexture {
  std::string name;                       // for statistics and trace headers (the spec's source)
  TextureSpec spec;                       // how to load it again (trace headers)
  std::shared_ptr<const Texture> texels;  // the levels; for a coefficient texture, its source's texels
  int coefficients_of = -1;               // bspline coefficient texture: the source texture's index
};

struct Frame {
  Registers regs;
  TextureMemory memory;
  std::vector<FrameTexture> textures;  // one per texture descriptor
  int line_bytes = 64;                 // the cache line the textures were tiled for
};

class FrameBuilder {
 public:
  // Tiled textures are stored in tiles of one `line_bytes` cache line (64, 256 or 1024).
  explicit FrameBuilder(int line_bytes = 64);
  // Places a texture (once per object) and returns its descriptor index.
  int add_texture(std::shared_ptr<const Texture> tex, TextureSpec spec);
  // Adds a sampler descriptor (equal descriptors share an index unless !share_equal).
  int add_sampler(const SamplerDescriptor& s, bool share_equal = true);
  // The texture descriptor a request of (texture, sampler) reads: the texture itself or, for a CUBIC
  // bspline-interp sampler, the coefficient texture of it for the sampler's wraps (made once).
  int bind(int texture, int sampler);
  const Frame& frame() const { return frame_; }
  Frame finish() { return std::move(frame_); }

 private:
  Frame frame_;
  // The caller's texture objects placed so far, each held (not only its address: a freed texture's
  // address may be reused by the next one) with its descriptor index.
  std::map<std::shared_ptr<const Texture>, int> placed_;
  std::map<std::tuple<int, WrapMode, WrapMode>, int> coefficients_;
};

// Rewrites the texture index of every request through FrameBuilder::bind.
void bind_requests(FrameBuilder& b, Trace& trace);

// The frame a trace's header describes: "# tfu-texture N SPEC ..." and "# tfu-sampler N ..." lines
// (texture specs relative to the trace's directory), descriptor N for binding N (indices 0..max,
// each bound at most once, every index a request uses bound). `defaults` supplies texture 0 and
// sampler 0 when the trace binds none (the command line's --texture and sampler options).
// Requests are bound (bind_requests) in place.
struct FrameDefaults {
  std::optional<TextureSpec> texture;
  std::optional<Params> sampler;
  std::optional<FilterMode> filter;  // replaces every sampler's filter mode
  Params sampler_overrides;          // applied over every sampler (e.g. edge_shape from --shape-policy)
  std::string game_dir;              // OpenArena data of oa:MAP:... textures (empty: $TFU_OPENARENA_DIR or Debian's)
};
Frame frame_from_trace(Trace& trace, const FrameDefaults& defaults, int line_bytes = 64);

// The header lines that describe a frame (for write_trace): one per texture that is not a
// coefficient texture, one per sampler.
void describe_frame(const Frame& f, Trace& trace);

}  // namespace tfu
