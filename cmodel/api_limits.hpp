// The sampling limits a Vulkan driver of this unit reports in VkPhysicalDeviceLimits, each derived
// from the datapath constant that fixes it (docs/sampler.md, "API limits"; Vulkan spec, "Limits").
//   subTexelPrecisionBits  the address generator keeps kSubTexelBits fraction bits of u - 1/2
//                          (dp::texel_coord): 2^8 positions between two texel centres
//   mipmapPrecisionBits    lambda is Q.kLodFracBits and the level blend weight is its fraction
//                          (select_levels, dp::level_blend)
//   maxSamplerLodBias      the LOD unit saturates each derivative magnitude at kDerivativeClamp
//                          (Q.16 texels), so lambda_base is at most log2(2^31 / 2^16) = 15; a larger
//                          footprint must still reach the last level of the longest chain
//                          (kMaxLevels - 1 = 14) after a negative bias: |bias| <= 15 - 14 = 1. (The
//                          positive side allows 3: a footprint of 2^-B texels has 2^(16 - B) LSBs of
//                          Q.16, and its quantization stays within the spec's 1/256 of a level with
//                          the log2 unit's error for B <= 3; docs/sampler.md.) Below Vulkan's core 2.
//   maxSamplerAnisotropy   the probe count register holds 1..kMaxAniso
//   maxImageDimension2D    kMaxTextureSize texels per side
// testbench/test_spec_bounds.cpp checks each against the datapath it comes from, and shows that a
// bias one step beyond maxSamplerLodBias leaves the Vulkan spec's bounds.
#pragma once

#include <bit>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/texture.hpp"

namespace tfu::api_limits {

inline constexpr int kSubTexelPrecisionBits = dp::kSubTexelBits;
inline constexpr int kMipmapPrecisionBits = kLodFracBits;
// The LOD unit's derivatives are Q.16 texels (derivatives_from_quad / _from_gradients).
inline constexpr int kDerivativeFracBits = 16;
// log2 of the largest derivative magnitude in texels: lambda_base saturates here.
inline constexpr int kLambdaBaseSaturation = std::bit_width(kDerivativeClamp) - kDerivativeFracBits;
inline constexpr int kMaxSamplerLodBias = kLambdaBaseSaturation - (kMaxLevels - 1);
inline constexpr int kMaxSamplerAnisotropy = kMaxAniso;
inline constexpr int kMaxImageDimension2D = kMaxTextureSize;

// One row per limit: the value, what Vulkan requires of it (core minimum; Roadmap 2022 / Vulkan 1.4
// where it is higher) and where the value comes from. limits_markdown() is the table in
// docs/sampler.md, "API limits" (a test checks it is pasted there).
struct LimitRow {
  const char* name;
  int value;
  int core_minimum, roadmap_minimum;
  const char* from;
};
// `from` is a format string: {0} is kLambdaBaseSaturation, {1} the last level of the longest chain.
inline constexpr LimitRow kLimits[] = {
    {"subTexelPrecisionBits", kSubTexelPrecisionBits, 4, 8,
     "`dp::kSubTexelBits`: the fraction bits of u - 1/2 the address generator keeps (`dp::texel_coord`)"},
    {"mipmapPrecisionBits", kMipmapPrecisionBits, 4, 6,
     "`kLodFracBits`: the fraction bits of lambda; the level blend weight is that fraction (`select_levels`)"},
    {"maxSamplerLodBias", kMaxSamplerLodBias, 2, 14,
     "`kDerivativeClamp`: derivative magnitudes saturate there (Q.16 texels), lambda_base at {0}, and a footprint "
     "beyond it must still reach the last level of the longest chain, {1} (`kMaxLevels` - 1), after the bias"},
    {"maxSamplerAnisotropy", kMaxSamplerAnisotropy, 16, 16, "`kMaxAniso`: the `max_aniso_m1` register"},
    {"maxImageDimension1D", kMaxImageDimension2D, 4096, 8192, "`kMaxTextureSize` (a W x 1 texture)"},
    {"maxImageDimension2D", kMaxImageDimension2D, 4096, 8192, "`kMaxTextureSize`"},
};

inline std::string limits_markdown() {
  std::string s = "| limit | value | Vulkan core / Roadmap 2022 minimum | from |\n|---|---:|---|---|\n";
  for (const LimitRow& r : kLimits)
    s += fmt::format(
        "| {} | {} | {} / {}{} | {} |\n", r.name, r.value, r.core_minimum, r.roadmap_minimum,
        r.value < r.core_minimum ? " (below core)" : (r.value < r.roadmap_minimum ? " (below Roadmap 2022)" : ""),
        fmt::format(fmt::runtime(r.from), kLambdaBaseSaturation, kMaxLevels - 1));
  return s;
}

}  // namespace tfu::api_limits
