// The GL fixed-function texture environment (OpenGL 1.5 Sec. 3.13, Tables 3.22-3.23, with
// GL_RGB_SCALE of the combine extension): how a material's texture stages combine. Stage k takes
// the previous stage's colour Cp (stage 0: the fragment's primary colour, white) and its filtered
// texel Cs (RGBA; an L8 texel arrives as (L, L, L, 1)):
//   replace   Cv = Cs               Av = As
//   modulate  Cv = Cp Cs            Av = Ap As
//   add       Cv = min(1, Cp + Cs)  Av = Ap As
//   decal     Cv = Cp (1 - As) + Cs As   Av = Ap
// then Cv = min(1, Cv * rgb_scale) (rgb_scale 1, 2 or 4; alpha is not scaled).
// Integer datapath on 8-bit codes (1.0 = 255): products and the decal blend are rounded to nearest
// with the division-free form of unorm::mul8_divfree, r = (i + (i >> 8)) >> 8 with i = x + 128,
// exact for every x <= 255 * 255 (tested exhaustively); the double form is the ground truth's.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "cmodel/texture.hpp"

namespace tfu {

enum class TexEnv { Replace, Modulate, Add, Decal };
inline constexpr EnumNames<TexEnv, 4> kTexEnvNames{
    "texture environment",
    {{{TexEnv::Replace, "replace"}, {TexEnv::Modulate, "modulate"}, {TexEnv::Add, "add"}, {TexEnv::Decal, "decal"}}}};
TexEnv tex_env_from_name(const std::string& name);  // kTexEnvNames
const char* tex_env_name(TexEnv e);

struct StageCombine {
  TexEnv env = TexEnv::Modulate;
  int rgb_scale = 1;  // 1, 2 or 4
  friend constexpr bool operator==(const StageCombine&, const StageCombine&) = default;
};

// round(x / 255) for 0 <= x <= 255 * 255, without a divider.
constexpr uint32_t div255_round(uint32_t x) {
  const uint32_t i = x + 128;
  return (i + (i >> 8)) >> 8;
}

constexpr Rgba8 combine_stage(Rgba8 prev, Rgba8 tex, StageCombine c) {
  const auto mul = [](uint8_t a, uint8_t b) { return div255_round(uint32_t{a} * b); };
  const auto add = [](uint8_t a, uint8_t b) { return std::min<uint32_t>(255, uint32_t{a} + b); };
  const auto decal = [a = tex.a](uint8_t p, uint8_t s) { return div255_round(uint32_t{p} * (255u - a) + uint32_t{s} * a); };
  uint32_t r = 0, g = 0, b = 0, al = 0;
  switch (c.env) {
    case TexEnv::Replace: r = tex.r, g = tex.g, b = tex.b, al = tex.a; break;
    case TexEnv::Modulate: r = mul(prev.r, tex.r), g = mul(prev.g, tex.g), b = mul(prev.b, tex.b), al = mul(prev.a, tex.a); break;
    case TexEnv::Add: r = add(prev.r, tex.r), g = add(prev.g, tex.g), b = add(prev.b, tex.b), al = mul(prev.a, tex.a); break;
    case TexEnv::Decal: r = decal(prev.r, tex.r), g = decal(prev.g, tex.g), b = decal(prev.b, tex.b), al = prev.a; break;
  }
  const auto scale = [s = static_cast<uint32_t>(c.rgb_scale)](uint32_t v) { return static_cast<uint8_t>(std::min<uint32_t>(255, v * s)); };
  return {scale(r), scale(g), scale(b), static_cast<uint8_t>(al)};
}

// The same in real arithmetic (channels in [0, 1]): the ground truth's and the ideal path's.
inline std::array<double, 4> combine_stage(const std::array<double, 4>& p, const std::array<double, 4>& s, StageCombine c) {
  std::array<double, 4> v{};
  for (size_t i = 0; i < 3; ++i) {
    switch (c.env) {
      case TexEnv::Replace: v[i] = s[i]; break;
      case TexEnv::Modulate: v[i] = p[i] * s[i]; break;
      case TexEnv::Add: v[i] = std::min(1.0, p[i] + s[i]); break;
      case TexEnv::Decal: v[i] = p[i] * (1.0 - s[3]) + s[i] * s[3]; break;
    }
    v[i] = std::min(1.0, v[i] * c.rgb_scale);
  }
  v[3] = c.env == TexEnv::Replace ? s[3] : (c.env == TexEnv::Decal ? p[3] : p[3] * s[3]);
  return v;
}

inline constexpr Rgba8 kPrimaryColour{255, 255, 255, 255};  // the fragment colour stage 0 combines with

}  // namespace tfu
