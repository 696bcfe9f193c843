// Named parameters of textures and samplers: one table each, read by the scene JSON ("texture" and
// "sampler" objects of a stage), by request-trace headers ("# tfu-texture", "# tfu-sampler") and by
// the command line (--filter, --wrap-s, ... are the same keys), and written back into trace
// headers. docs/traces.md and docs/renderer.md list the keys.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>

#include "cmodel/descriptors.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

using Params = std::map<std::string, std::string>;

// ---- Samplers ----
struct SamplerParam {
  const char* key;
  const char* meaning;
  void (*set)(SamplerDescriptor& s, const std::string& value);  // throws InputError (without the key)
  std::string (*get)(const SamplerDescriptor& s);
};
std::span<const SamplerParam> sampler_params();
// Sets one key (InputError without a location: "unknown sampler key ..." or the value's problem).
void set_sampler_param(SamplerDescriptor& s, const std::string& key, const std::string& value);
// Applies `params` over `base`; an unknown key or bad value is an InputError "WHERE: key 'k': ...".
SamplerDescriptor sampler_from_params(const Params& params, const std::string& where, SamplerDescriptor base = {});
// Every key with its value (what a trace header records).
Params sampler_to_params(const SamplerDescriptor& s);

// ---- Textures ----
// "proc:NAME[:SIZE]" (a procedural texture with its analytic function, procedural.hpp) or an image
// file (relative to `base_dir`), with the keys format (auto | rgba8 | l8 | vs16x2: reinterpret the
// file's bytes), mipmaps (auto: the file's stored levels, else box | stored | none | box | gaussian |
// edge), alpha (Lee & Jen Eq. 7 weight for mipmaps=edge), layout (tiled | linear) and tile_bytes
// (64 | 256 | 1024).
struct TextureSpec {
  std::string source;  // as given
  Params params;
};
std::span<const char* const> texture_param_keys();
struct LoadedTexture {
  std::shared_ptr<const Texture> texture;
  ColourFn truth;  // analytic colour (procedural textures), empty for files
};
// The keys format, mipmaps, alpha, layout, tile_bytes and compress applied to a texture's level 0
// (or to a file's stored levels), as load_texture_spec applies them to what it loaded: also for
// textures made in memory (the Python module's numpy arrays). InputError "WHERE: key 'k': ...".
Texture texture_with_params(Texture tex, const Params& params, const std::string& where);
// `base_dir`: where a relative file name is found; `game_dir`: the OpenArena data of oa:MAP:... textures
// (empty: $TFU_OPENARENA_DIR, else Debian's).
LoadedTexture load_texture_spec(const TextureSpec& spec, const std::string& where, const std::string& base_dir = {},
                                const std::string& game_dir = {});

}  // namespace tfu
