#include "cmodel/mipmap.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cmodel/edge_filter.hpp"
#include "cmodel/error.hpp"

namespace tfu {

MipMethod mip_method_from_name(const std::string& name) { return kMipMethodNames.from_name(name); }
const char* mip_method_name(MipMethod m) { return kMipMethodNames.name(m); }

namespace {

Texel4 texel(const Image& img, TexelFormat fmt, int x, int y) {
  return decode_texel(img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1)), fmt);
}

// Eq. 8 on the block at (2x, 2y); a side of length 1 contributes one texel.
Texel4 box_at(const Image& src, TexelFormat fmt, int x, int y) {
  const int x0 = src.width > 1 ? 2 * x : x, y0 = src.height > 1 ? 2 * y : y;
  const int nx = src.width > 1 ? 2 : 1, ny = src.height > 1 ? 2 : 1;
  const int shift = (nx == 2) + (ny == 2);
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    int32_t sum = 0;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) sum += texel(src, fmt, x0 + i, y0 + j)[ch];
    out[ch] = (sum + ((1 << shift) >> 1)) >> shift;
  }
  return out;
}

Texel4 gaussian_at(const Image& src, TexelFormat fmt, int x, int y) {
  constexpr std::array<int32_t, 4> k{1, 3, 3, 1};
  const bool fx = src.width > 1, fy = src.height > 1;
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    int32_t sum = 0;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const int sx = fx ? 2 * x - 1 + i : x, sy = fy ? 2 * y - 1 + j : y;
        sum += k[static_cast<size_t>(i)] * k[static_cast<size_t>(j)] * texel(src, fmt, sx, sy)[ch];
      }
    out[ch] = (sum + 32) >> 6;
  }
  return out;
}

Texel4 edge_at(const Image& src, TexelFormat fmt, int x, int y) {
  std::array<Texel4, lee_jen::kTexels> c{};
  const int cx = src.width > 1 ? 2 * x : x, cy = src.height > 1 ? 2 * y : y;
  for (int n = 1; n <= lee_jen::kTexels; ++n) {
    const lee_jen::TexelPos p = lee_jen::texel_pos(n);
    c[static_cast<size_t>(n - 1)] = texel(src, fmt, cx + p.x, cy + p.y);
  }
  // Centre of the even square: fu = fv = 1/2 (for a side of length 1 the fraction is 0).
  return lee_jen::edge_preserving_interpolate(c, lee_jen::kAllTexels, src.width > 1 ? 128u : 0u,
                                              src.height > 1 ? 128u : 0u, fmt);
}

}  // namespace

Image downsample(const Image& src, TexelFormat fmt, MipMethod method, int alpha_q8) {
  Image dst(std::max(1, src.width / 2), std::max(1, src.height / 2));
  for (int y = 0; y < dst.height; ++y)
    for (int x = 0; x < dst.width; ++x) {
      Texel4 v;
      switch (method) {
        case MipMethod::Box: v = box_at(src, fmt, x, y); break;
        case MipMethod::Gaussian: v = gaussian_at(src, fmt, x, y); break;
        case MipMethod::Edge: {
          const Texel4 g = box_at(src, fmt, x, y), e = edge_at(src, fmt, x, y);
          for (size_t ch = 0; ch < 4; ++ch) v[ch] = ((256 - alpha_q8) * g[ch] + alpha_q8 * e[ch] + 128) >> 8;  // Eq. 7
          break;
        }
      }
      dst.at(x, y) = encode_texel(v, fmt);
    }
  return dst;
}

void generate_mipmaps(Texture& tex, MipMethod method, double alpha) {
  if (!(alpha >= 0.0 && alpha <= 1.0))
    throw InputError(fmt::format("MIP alpha {} is outside [0, 1]", alpha));
  // Lee & Jen's edge weights are defined on 8-bit channels, not on SRGBA8's linear unorm12
  // (filters_format, cmodel/descriptors.hpp).
  if (method == MipMethod::Edge && tex.format == TexelFormat::SRGBA8)
    throw InputError(
        fmt::format("edge-preserving MIP-maps are not defined on {} textures", texel_format_name(tex.format)));
  const int a = static_cast<int>(std::lround(alpha * 256.0));
  tex.levels.resize(1);
  const int n = mip_level_count(tex.width(), tex.height());
  for (int l = 1; l < n; ++l) tex.levels.push_back(downsample(tex.levels.back(), tex.format, method, a));
}

}  // namespace tfu
