#include "cmodel/aniso.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace tfu {

namespace {

int clamp_max_aniso(int max_aniso) { return std::clamp(max_aniso, 1, kMaxAniso); }

__extension__ using u128 = unsigned __int128;

// n^2 (8 + t)^2 pmin2 >= 64 pmax2, exactly: n^2 <= 2^8, (8 + t)^2 < 2^8, pmin2, pmax2 < 2^64, so
// both sides fit 80 bits (79 for the descriptor's 63-bit lengths). For t = 0 this is n^2 pmin2 >=
// pmax2, the spec's ceil.
bool covers(uint64_t pmin2, uint64_t pmax2, uint64_t n2, uint32_t threshold_scale) {
  return u128{n2} * threshold_scale * pmin2 >= u128{pmax2} << 6;
}

}  // namespace

int aniso_probe_count(uint64_t pmax2_q32, uint64_t pmin2_q32, const AnisoParams& p) {
  const uint32_t scale = aniso_threshold_scale(p.aniso_threshold);
  int n = 1;
  while (n <= kMaxAniso && !covers(pmin2_q32, pmax2_q32, static_cast<uint64_t>(n) * static_cast<uint64_t>(n), scale)) ++n;
  n = std::min(n, clamp_max_aniso(p.max_aniso));  // n = 17 (no n covers) becomes maxAniso
  if (p.aniso_rounding == AnisoRounding::PowerOfTwo) n = static_cast<int>(std::bit_ceil(static_cast<unsigned>(n)));
  return n;
}

DotCross aniso_dot_cross(const TexelDerivatives& d) {
  const auto clamp_signed = [](int64_t v) {
    const auto m = static_cast<int64_t>(derivative_magnitude(v));
    return v < 0 ? -m : m;
  };
  const int64_t ux = clamp_signed(d.dudx), vx = clamp_signed(d.dvdx), uy = clamp_signed(d.dudy), vy = clamp_signed(d.dvdy);
  // Each product < 2^62 in magnitude; a sum or difference of two < 2^63: no overflow.
  return {ux * uy + vx * vy, ux * vy - vx * uy};
}

AnisoU128 aniso_hypot(uint64_t e, uint64_t f) {
  const uint64_t big = std::max(e, f), small = std::min(e, f);
  const int s = std::max(0, static_cast<int>(std::bit_width(big)) - 16);  // 0..48
  const uint64_t big_m = big >> s, small_m = small >> s;                 // 16-bit mantissas, truncated
  const uint64_t h = axis_length_q16(big_m * big_m + small_m * small_m);  // 17 bits, h >= big_m
  return AnisoU128{big} + (AnisoU128{h - big_m} << s);                     // (h - big_m) < 2^15
}

uint64_t ellipse_major_len2(uint64_t px2_q32, uint64_t py2_q32, int64_t dot_q32) {
  const AnisoU128 a = AnisoU128{px2_q32} + py2_q32;  // < 2^64 for the clamped magnitudes
  const uint64_t e = px2_q32 >= py2_q32 ? px2_q32 - py2_q32 : py2_q32 - px2_q32;
  const uint64_t f = 2 * (dot_q32 < 0 ? uint64_t{0} - static_cast<uint64_t>(dot_q32) : static_cast<uint64_t>(dot_q32));
  const AnisoU128 h = std::min(aniso_hypot(e, f), a);  // H <= A in exact terms (4 D^2 >= 0)
  return static_cast<uint64_t>((a + h) >> 1);
}

int aniso_probe_count_ellipse(uint64_t pmax2_q32, uint64_t det_q32, const AnisoParams& p) {
  // n (8 + t) |D| >= 8 Pmax'^2: n <= 16, 8 + t <= 15, |D| < 2^63: < 2^71; 8 Pmax'^2 < 2^67.
  const auto scale = static_cast<uint32_t>(8 + std::clamp(p.aniso_threshold, 0, kAnisoThresholdMax));
  int n = 1;
  while (n <= kMaxAniso && u128{static_cast<uint64_t>(n)} * scale * det_q32 < u128{pmax2_q32} << 3) ++n;
  n = std::min(n, clamp_max_aniso(p.max_aniso));  // n = 17 (no n covers) becomes maxAniso
  if (p.aniso_rounding == AnisoRounding::PowerOfTwo) n = static_cast<int>(std::bit_ceil(static_cast<unsigned>(n)));
  return n;
}

const std::array<int32_t, kMaxAniso>& aniso_log2_sq_rom() {
  // Offline table generation (double precision), the one source of the ROM contents.
  static const auto rom = [] {
    std::array<int32_t, kMaxAniso> r{};
    for (size_t k = 0; k < r.size(); ++k)
      r[k] = static_cast<int32_t>(std::floor(512.0 * std::log2(static_cast<double>(k + 1)) + 0.5));
    return r;
  }();
  return rom;
}

int32_t aniso_lambda(uint64_t pmax2_q32, int n) {
  return lambda_from_length_sq(pmax2_q32, aniso_log2_sq_rom()[static_cast<size_t>(n - 1)]);
}

AnisoLod aniso_lod(const TexelDerivatives& d, const AnisoParams& p) {
  AnisoLod a;
  a.px2_q32 = derivative_length_sq(d.dudx, d.dvdx);
  a.py2_q32 = derivative_length_sq(d.dudy, d.dvdy);
  a.major_x = a.px2_q32 >= a.py2_q32;
  const auto clamp_signed = [](int64_t v) {
    const auto m = static_cast<int64_t>(derivative_magnitude(v));
    return v < 0 ? -m : m;
  };
  a.major_du_q16 = clamp_signed(a.major_x ? d.dudx : d.dudy);
  a.major_dv_q16 = clamp_signed(a.major_x ? d.dvdx : d.dvdy);
  if (p.aniso_axes == AnisoAxes::Ellipse) {
    const DotCross dc = aniso_dot_cross(d);
    a.pmax2_q32 = ellipse_major_len2(a.px2_q32, a.py2_q32, dc.dot_q32);
    a.det_q32 = dc.det_q32 < 0 ? uint64_t{0} - static_cast<uint64_t>(dc.det_q32) : static_cast<uint64_t>(dc.det_q32);
    a.probes = aniso_probe_count_ellipse(a.pmax2_q32, a.det_q32, p);
  } else {
    a.pmax2_q32 = std::max(a.px2_q32, a.py2_q32);
    a.probes = aniso_probe_count(a.pmax2_q32, std::min(a.px2_q32, a.py2_q32), p);
  }
  a.lambda_q8 = aniso_lambda(a.pmax2_q32, a.probes);
  return a;
}

uint32_t axis_length_q16(uint64_t len2_q32) {
  // Digit-by-digit (restoring) square root: one result bit per step, exact floor.
  uint64_t rem = len2_q32, root = 0;
  uint64_t bit = uint64_t{1} << 62;
  while (bit > rem) bit >>= 2;
  while (bit != 0) {
    if (rem >= root + bit) {
      rem -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<uint32_t>(root);
}

int64_t probe_offset_q16(int64_t major_q16, int n, int i) {
  return dp::scale_probe_fraction(major_q16, probe_rom()[static_cast<size_t>(probe_rom_address(n, i))].frac_q16);
}

ProbeOffset probe_offset(const AnisoLod& a, int i) {
  return {probe_offset_q16(a.major_du_q16, a.probes, i), probe_offset_q16(a.major_dv_q16, a.probes, i)};
}

namespace dp {

void AnisoAccumulator::add(const Texel4& c, int n, int i) {
  const int64_t w = probe_rom()[static_cast<size_t>(probe_rom_address(n, i))].weight;
  for (size_t ch = 0; ch < 4; ++ch) acc[ch] += w * c[ch];
}

Texel4 AnisoAccumulator::result() const {
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch)
    out[ch] = static_cast<int32_t>((acc[ch] + (1 << (kAnisoWeightBits - 1))) >> kAnisoWeightBits);
  return out;
}

Texel4 aniso_average(const Texel4* probes, int n) {
  AnisoAccumulator a;
  for (int i = 1; i <= n; ++i) a.add(probes[i - 1], n, i);
  return a.result();
}

}  // namespace dp
}  // namespace tfu
