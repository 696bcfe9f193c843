// Command-line options that describe a texture and a sampler, shared by `tfu sample` and the cycle
// simulator's commands: one definition, so both read the same texture and configure the same unit.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cmodel/sampler.hpp"
#include "cmodel/texture.hpp"

namespace tfu::cli {

struct TextureOptions {
  std::string texture;            // image file path, or proc:NAME[:SIZE] for a procedural texture
  std::string format = "auto";    // auto | rgba8 | l8 | vs16x2 (reinterpret the file's bytes)
  std::string mipmaps = "auto";   // auto (stored levels, else box) | stored | none | box | gaussian | edge
  double alpha = 0.5;             // edge-preserving MIP blend (Lee & Jen Eq. 7)
  std::string layout = "tiled";   // memory layout: linear | tiled
  int tile_bytes = 64;            // tiled: bytes per tile (one cache line): 64, 256, 1024
};

struct SamplerOptions {
  std::string filter = "LINEAR";
  std::string kernel = "catmull-rom";
  std::string wrap = "repeat";
  std::string wrap_s, wrap_t;  // override --wrap per axis
  std::string border = "0,0,0,0";
  double lod_bias = 0, min_lod = -1000, max_lod = 1000;
  int rom_samples = 64;
  unsigned rom_bits = 8;
  std::string rom_recon = "nearest";
  std::string edge_shape = "static";
  int max_aniso = 1;
};

void add_texture_options(CLI::App& cmd, TextureOptions& o);
void add_sampler_options(CLI::App& cmd, SamplerOptions& o);
Texture load_texture_spec(const std::string& spec);  // file path or proc:NAME[:SIZE]
Texture load_texture_from_options(const TextureOptions& o);
SamplerDescriptor sampler_config_from_options(const SamplerOptions& o);

}  // namespace tfu::cli
