// Procedural textures for the scene renderer (docs/renderer.md): each generator returns a one-level
// RGBA8 texture AND the analytic colour function it was sampled from, so that a supersampled ground
// truth can be computed without any texture filter.
//
// Conventions (texture.hpp): texel (i, j) holds round(255 eval((i + 0.5) / N, (j + 0.5) / N)), i.e.
// the function point-sampled at the texel centre (t = 0 is the top row). eval() returns RGBA in
// [0, 1] and repeats with period 1 in s and t (eval(s + 1, t) == eval(s, t)).
//
// The exception is `text`: glyph outlines have no closed form here, so the text is rendered by
// OpenImageIO (FreeType, DejaVu Sans) into a 4x-oversampled 8-bit coverage image; the texture is the
// 4x4 box average of that image and eval() is a bilinear lookup into it (repeat wrap). The ground
// truth of text scenes is therefore exact up to the 1/4-texel detail of the oversampled rendering.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "cmodel/texture.hpp"

namespace tfu {

using ColourFn = std::function<std::array<double, 4>(double s, double t)>;

struct Procedural {
  std::string name;
  Texture texture;  // one level, RGBA8, size x size
  ColourFn eval;    // analytic colour, period 1 in s and t
};

// Checkerboard of cells x cells squares, (0.9, 0.9, 0.9) and (0.1, 0.1, 0.1) (GPU Gems Fig. 25-1).
Procedural make_checkerboard(int size, int cells);
// Black lines of text on white (Lee & Jen Figs. 6 and 8): `lines` lines of DejaVu Sans.
Procedural make_text(int size, int lines);
// Zone plate 0.5 + 0.5 cos(pi N r^2), r = distance from the texture centre: the local frequency
// reaches the texture's Nyquist rate (1/2 cycle per texel) at the edge midpoints.
Procedural make_zoneplate(int size);
// Smooth light-map: a low-frequency periodic gradient plus four Gaussian light spots (Hadwiger Fig. 3).
Procedural make_lightmap(int size);
// Value noise: a cells x cells lattice of hashed values, C1 (smoothstep) interpolated, two octaves.
Procedural make_noise(int size, int cells);
// MIP-level colours (the filter testers' tunnel texture): a full chain whose level L is one flat
// colour, mip_level_colour(L), so the colour of a trilinear result shows lambda (the blend of
// levels floor(lambda) and floor(lambda) + 1 by its fraction). size a power of two; the chain is
// the texture's own (load_texture_spec keeps it). eval() is level 0's colour: the supersampled
// truth of such a texture has no meaning beyond that.
Procedural make_mip_colours(int size);
Rgba8 mip_level_colour(int level);  // 12 distinct colours, repeating from level 12 on

// By name: checkerboard, text, zoneplate, lightmap, noise, mip_colours (each with its default parameters for
// the size). Unknown name or size outside 1..4096 -> InputError naming it.
Procedural make_procedural(const std::string& name, int size);
const std::vector<std::string>& procedural_names();

// Point-samples `eval` at the texel centres of a size x size RGBA8 level (round to nearest).
Texture texture_from_function(const ColourFn& eval, int size);

}  // namespace tfu
