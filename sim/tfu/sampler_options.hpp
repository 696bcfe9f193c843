// Command-line options that describe a texture and a sampler, shared by `tfu sample`, `tfu sim`
// and `tfu mipmap`: one flag per key of the texture and sampler tables of cmodel/bindings.hpp
// (`--wrap-s` is the key `wrap_s`), so the command line, scene files and trace headers accept the
// same names and values. Only the flags given count: the rest keep their defaults.
#pragma once

#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "cmodel/bindings.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/gl_replay.hpp"
#include "cmodel/trace.hpp"

namespace tfu::cli {

struct TextureOptions {
  std::string texture;                        // image file path, or proc:NAME[:SIZE]
  std::map<std::string, std::string> values;  // one per texture key (the flags' storage)
};

struct SamplerOptions {
  std::map<std::string, std::string> values;  // one per sampler key (the flags' storage)
  std::string wrap;                           // --wrap: wrap_s and wrap_t at once
};

// `texture_required`: --texture is mandatory (otherwise it may come from a trace's header).
// A game's OpenGL command stream (docs/gl-replay.md), the options tfu render and tfu sim share.
struct GlTraceOptions {
  std::string trace;   // an apitrace trace; empty: no GL replay
  int frame = 0;       // its frame replayed
  int alpha_bits = -1;  // the framebuffer's alpha bits (-1: as the trace's visual asks)
  std::string min_filter;  // the mipmapped textures' filter override (empty: as traced)
  int max_aniso = 0;       // their anisotropy override (0: as traced)
  std::string draws_out;   // a CSV of the frame's draws (gl::write_draw_table); empty: none
};
// --gl-trace, --frame, --alpha-bits, --gl-min-filter, --gl-max-aniso, --draws-out; `through` says
// which models the replay goes through.
void add_gl_trace_options(CLI::App& cmd, GlTraceOptions& o, const char* through);
// The replay's options from the command line's, textures tiled for `line_bytes` lines.
gl::ReplayOptions gl_replay_options(const GlTraceOptions& o, int line_bytes);
// The options above that need --gl-trace ("--frame" ...), for the "needs --gl-trace" check.
const std::vector<const char*>& gl_trace_only_options();

void add_texture_options(CLI::App& cmd, TextureOptions& o, bool texture_required = true);
void add_sampler_options(CLI::App& cmd, SamplerOptions& o);
// The texture the flags describe (the keys given), or nullopt without --texture.
std::optional<TextureSpec> texture_spec_given(const CLI::App& cmd, const TextureOptions& o);
// The sampler keys given (--wrap expands to wrap_s and wrap_t unless those are given).
Params sampler_params_given(const CLI::App& cmd, const SamplerOptions& o);
// The frame of a request trace (cmodel/frame.hpp): the textures and samplers its header binds, or,
// when it binds none, texture 0 from --texture and sampler 0 from the sampler flags. Sampler flags
// given with a trace that binds samplers override those keys of every bound sampler. Textures are
// tiled for `line_bytes` lines. The trace's requests are bound (bind_requests) in place. `game_dir`:
// the OpenArena data of a level trace's oa:MAP:... textures (--game-dir).
Frame frame_for_trace(const CLI::App& cmd, const TextureOptions& t, const SamplerOptions& s, Trace& trace, int line_bytes,
                      const std::string& game_dir = {});

// `--plain`: run the plain datapaths instead of every speed-only fast path (cmodel/fast_paths.hpp);
// it also sets TFU_PLAIN=1 so that processes this one starts (sweep points) run plain too.
void add_plain_option(CLI::App& cmd);

// The command-line flag of a table key: "wrap_s" -> "--wrap-s".
std::string flag_of(const std::string& key);

}  // namespace tfu::cli
