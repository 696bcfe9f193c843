// One randomized case of the spec-bound check (testbench/spec_bounds.hpp): a texture, a sampler and
// requests drawn from bytes, each request's golden-model result (Sampler::sample at the LOD unit's
// lambda) checked against the Vulkan spec's interval. Shared by the ctest
// (testbench/test_spec_bounds.cpp, random bytes) and the libFuzzer target fuzz_spec_bounds.
//   texture   RGBA8 or L8; 1..40 texels per side (non-powers of two included), or one side up to
//             16384 and the other 1..2 (up to 15 levels); texels random, black/white, ramps or a
//             few values; a box MIP chain or independent random levels, cut to 1..all levels
//   sampler   NEAREST / LINEAR, each plain, _MIPMAP_NEAREST and _MIPMAP_LINEAR; wrap per axis
//             (all four), border word; bias within +-bias_limit levels (the driver clamps a bias
//             to maxSamplerLodBias); min / max LOD each unbounded or in [-2, 16] levels
//   requests  1..64 of one kind: explicit LOD in [-4, 18], gradients or a 2x2 quad with a footprint
//             of 2^-12..2^18 texels per pixel in any direction (sometimes zero or axis-aligned);
//             coordinates uniform in [-2.5, 2.5], on the 1/64 grid, next to texel edges, up to
//             2^29 texels away, or any 32-bit pattern
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cmodel/api_limits.hpp"
#include "cmodel/error.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/sampler.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/spec_bounds.hpp"

namespace tfu::spec {

struct CaseResult {
  int64_t checked = 0;  // requests (quad pixels) checked against the bounds
  int64_t out_of_domain = 0;
  int64_t outside = 0;  // results outside the bounds
  std::string first;    // the first of them, described
};

namespace detail {

// Texel content from a seed (xorshift64): the fuzzer's bytes choose the kind and the seed.
struct TexelSource {
  uint64_t x;
  int kind;
  uint64_t next() {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  }
  Rgba8 texel(int i, int j, TexelFormat fmt) {
    const uint64_t r = next();
    std::array<uint8_t, 4> c{};
    for (size_t k = 0; k < 4; ++k) {
      const auto b = static_cast<uint8_t>(r >> (8 * k));
      switch (kind) {
        case 0: c[k] = b; break;                                                                  // random
        case 1: c[k] = b & 1 ? 255 : 0; break;                                                    // black / white
        case 2: c[k] = static_cast<uint8_t>(i * (7 + 13 * k) + j * (3 + 5 * k) + 40 * k); break;  // ramps
        default: c[k] = static_cast<uint8_t>((b % 3) * 127); break;                               // a few values
      }
    }
    if (fmt == TexelFormat::L8) return {c[0], c[0], c[0], 255};
    return {c[0], c[1], c[2], c[3]};
  }
};

inline Texture make_texture(fuzz::ByteReader& in) {
  Texture tex;
  tex.format = in.flag() ? TexelFormat::L8 : TexelFormat::RGBA8;
  int w, h;
  if (in.byte() % 8 == 0) {  // a long thin texture: up to 15 levels
    w = static_cast<int>(in.in_range(1, kMaxTextureSize));
    h = static_cast<int>(in.in_range(1, 2));
    if (in.flag()) std::swap(w, h);
  } else {
    w = static_cast<int>(in.in_range(1, 40));
    h = static_cast<int>(in.in_range(1, 40));
  }
  TexelSource src{in.u32() | (uint64_t{1} << 40), in.byte() % 4};
  const auto fill = [&](int lw, int lh) {
    Image img(lw, lh);
    for (int j = 0; j < lh; ++j)
      for (int i = 0; i < lw; ++i) img.at(i, j) = src.texel(i, j, tex.format);
    return img;
  };
  tex.levels.push_back(fill(w, h));
  const int count = mip_level_count(w, h);
  if (in.flag()) {
    generate_mipmaps(tex, MipMethod::Box);
  } else {
    for (int l = 1; l < count; ++l) tex.levels.push_back(fill(mip_extent(w, l), mip_extent(h, l)));
  }
  tex.levels.resize(static_cast<size_t>(in.in_range(1, static_cast<int64_t>(tex.levels.size()))));
  return tex;
}

inline SamplerDescriptor make_sampler(fuzz::ByteReader& in, int bias_limit) {
  SamplerDescriptor sd;
  sd.mode.base = in.flag() ? BaseFilter::Linear : BaseFilter::Nearest;
  sd.mode.mip = in.pick({MipMode::None, MipMode::Nearest, MipMode::Linear});
  constexpr WrapMode kWraps[] = {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge,
                                 WrapMode::ClampToBorder};
  sd.wrap_s = in.pick(kWraps);
  sd.wrap_t = in.pick(kWraps);
  sd.border = {in.byte(), in.byte(), in.byte(), in.byte()};
  sd.lod.bias_q8 = static_cast<int32_t>(in.in_range(-bias_limit * 256, bias_limit * 256));
  const auto clamp_lod = [&in](int32_t unbounded) {
    return in.flag() ? unbounded : static_cast<int32_t>(in.in_range(-2 * 256, 16 * 256));
  };
  sd.lod.min_lod_q8 = clamp_lod(-1000 * 256);
  sd.lod.max_lod_q8 = clamp_lod(1000 * 256);
  if (sd.lod.min_lod_q8 > sd.lod.max_lod_q8) std::swap(sd.lod.min_lod_q8, sd.lod.max_lod_q8);
  return sd;
}

inline float coordinate(fuzz::ByteReader& in, int size) {
  const uint8_t kind = in.byte();
  if (kind < 150) return static_cast<float>(in.u32()) * 0x1p-32f * 5.0f - 2.5f;
  if (kind < 200) return static_cast<float>(in.in_range(-160, 160)) / 64.0f;
  if (kind < 240) {  // within a few 2^-9 texels of a texel edge or centre
    const auto i = static_cast<float>(in.in_range(-2 * size, 3 * size));
    const float off = static_cast<float>(in.in_range(-4, 4)) * 0x1p-9f + (in.flag() ? 0.5f : 0.0f);
    return (i + off) / static_cast<float>(size);
  }
  if (kind < 252) {  // far away: up to 2^29 texels
    const auto e = static_cast<int>(in.in_range(1, 29)) - std::bit_width(static_cast<unsigned>(size));
    return std::ldexp(static_cast<float>(in.u32()) * 0x1p-32f - 0.5f, e);
  }
  return in.raw_float();  // any bit pattern: NaN, infinities, denormals (outside the domain when not finite)
}

// A footprint of 2^e texels per pixel, e in [-12, 18] in 1/16 steps, at an angle (derivative in
// normalized coordinates: texels / size).
inline std::array<float, 4> derivatives(fuzz::ByteReader& in, int w, int h) {
  const uint8_t shape = in.byte();
  if (shape < 8) return {0, 0, 0, 0};
  const double len_x = std::exp2(static_cast<double>(in.in_range(-12 * 16, 18 * 16)) / 16.0);
  const double len_y = std::exp2(static_cast<double>(in.in_range(-12 * 16, 18 * 16)) / 16.0);
  double ax = static_cast<double>(in.u32()) * 0x1p-32 * 6.283185307179586, ay = ax + 1.5707963267948966;
  if (shape < 40) ax = 0, ay = 1.5707963267948966;  // axis-aligned
  if (shape >= 40 && shape < 80) ay = static_cast<double>(in.u32()) * 0x1p-32 * 6.283185307179586;
  return {static_cast<float>(len_x * std::cos(ax) / w), static_cast<float>(len_x * std::sin(ax) / h),
          static_cast<float>(len_y * std::cos(ay) / w), static_cast<float>(len_y * std::sin(ay) / h)};
}

inline void check(const Texture& tex, const SamplerDescriptor& sd, const Sampler& sm, float s, float t,
                  const LodInput& lod, int32_t lambda_q8, CaseResult& res) {
  if (!in_domain(tex, s, t, lod)) {
    ++res.out_of_domain;
    return;
  }
  ++res.checked;
  const Texel4 got = decode_texel(sm.sample(s, t, lambda_q8), tex.format);
  const Bounds b = filter_bounds(tex, sd, s, t, lod);
  if (b.contains(got)) return;
  if (res.outside++ == 0)
    res.first = fmt::format("{}: golden ({}, {}, {}, {}) outside [{}..{}, {}..{}, {}..{}, {}..{}] (lambda_q8 {})",
                    describe(tex, sd, s, t, lod), got[0], got[1], got[2], got[3], b.lo[0], b.hi[0], b.lo[1], b.hi[1],
                    b.lo[2], b.hi[2], b.lo[3], b.hi[3], lambda_q8);
}

}  // namespace detail

// Draws one case from `in` and checks every request; bias within +-bias_limit levels.
inline CaseResult run_case(fuzz::ByteReader& in, int bias_limit = api_limits::kMaxSamplerLodBias) {
  CaseResult res;
  const Texture tex = detail::make_texture(in);
  const SamplerDescriptor sd = detail::make_sampler(in, bias_limit);
  const Sampler sm(tex, sd);
  const int w = tex.width(), h = tex.height();
  const auto kind = in.pick({LodKind::Explicit, LodKind::Gradients, LodKind::Quad});
  const auto n = in.in_range(1, 64);
  for (int64_t r = 0; r < n; ++r) {
    LodInput lod;
    lod.kind = kind;
    const float s = detail::coordinate(in, w), t = detail::coordinate(in, h);
    if (kind == LodKind::Explicit) {
      lod.lod = in.flag() ? static_cast<float>(in.in_range(-4 * 64, 18 * 64)) / 64.0f
                          : static_cast<float>(in.u32()) * 0x1p-32f * 22.0f - 4.0f;
      detail::check(tex, sd, sm, s, t, lod, lambda_explicit(lod.lod), res);
      continue;
    }
    const std::array<float, 4> d = detail::derivatives(in, w, h);
    if (kind == LodKind::Gradients) {
      lod.dsdx = d[0], lod.dtdx = d[1], lod.dsdy = d[2], lod.dtdy = d[3];
      detail::check(tex, sd, sm, s, t, lod, lambda_from_gradients(d[0], d[1], d[2], d[3], w, h), res);
      continue;
    }
    lod.qs = {s, s + d[0], s + d[2], s + d[0] + d[2]};
    lod.qt = {t, t + d[1], t + d[3], t + d[1] + d[3]};
    const int32_t lambda = lambda_from_quad(lod.qs.data(), lod.qt.data(), w, h);
    for (size_t k = 0; k < 4; ++k) detail::check(tex, sd, sm, lod.qs[k], lod.qt[k], lod, lambda, res);
  }
  return res;
}

}  // namespace tfu::spec
