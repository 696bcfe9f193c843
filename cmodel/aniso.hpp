// Anisotropic LOD unit and probe generator (EXT_texture_filter_anisotropic, Sec. 3.8.5 as changed
// by the extension; probes along the major axis as in Schilling et al. 1996 "Texram" and McCormack
// et al. 1999 "Feline"), in fixed point. Pure functions: the golden sampler, the cycle model's LOD
// unit and address generator and rtl/sv/aniso/ all compute these bits. docs/anisotropic.md.
//
// Reference (EXT spec):  Px = |(du/dx, dv/dx)|, Py = |(du/dy, dv/dy)| (texels),
//   Pmax = max(Px, Py), Pmin = min(Px, Py), N = min(ceil(Pmax / Pmin), maxAniso),
//   lambda' = log2(Pmax / N), and N samples at u(x - 1/2 + i/(N+1), y), i = 1..N (x major), averaged.
//
// Datapath (all integer):
//   derivatives      Q.16 level-0 texels (lod.hpp TexelDerivatives), magnitudes clamped to 2^31 - 1
//   Px^2, Py^2       |du|^2 + |dv|^2, Q.32, < 2^63 (lod.hpp derivative_length_sq; no square root)
//   major axis       x if Px^2 >= Py^2, else y (ties: x)
//   N                smallest n in 1..16 with n^2 Pmin^2 >= Pmax^2 (exact: 15 compares of 71-bit
//                    products), 16 + 1 if none, then min(., maxAniso); aniso_rounding
//                    PowerOfTwo: rounded UP to a power of two (the spec's "round N up to the nearest supported sampling rate");
//                    aniso_threshold t (0..7, 0 = the spec's N): smallest n with n (1 + t/8) Pmin >= Pmax,
//                    compared as n^2 (8 + t)^2 Pmin^2 >= 64 Pmax^2 (79-bit products)
//   lambda           (log2_q8(Pmax^2) - 32 * 256 - R[N] + 1) >> 1, R[N] = round(512 log2 N) from a
//                    16-entry ROM (R[1] = 0: N = 1 is the isotropic lambda bit for bit);
//                    |lambda - 256 log2(Pmax / N)| <= 0.45 + 0.25 + 0.5 = 1.2 LSB of Q.8 (log2 ROM,
//                    R ROM, halving); 1.09 measured (test_aniso)
//   probe offset     o_i = sgn * ((|d| |q(N, i)| + 2^15) >> 16), Q.16 level-0 texels, d the major
//                    derivative vector (per component), q(N, i) = round-half-away(2^16 (2i - N - 1) /
//                    (2 (N + 1))) from the probe ROM; sign-magnitude so that the probes stay exactly
//                    symmetric about the centre
//   on level L       sgn * ((|o| + 2^(7 + L)) >> (8 + L)): Q.8 texels of level L, added to
//                    dp::texel_coord's u = floor(s W_L 2^8) - 128
//   average          c = (sum_i w_i c_i + 128) >> 8 per channel, w_i from the probe ROM, sum w_i = 256
//
// Ellipse axes (aniso_axes Ellipse; the spec's Px, Py are lengths along the screen axes, not the
// footprint ellipse's axes, so its lambda depends on the angle of the ellipse against the screen).
// The ellipse's axes follow from the two derivative vectors a = (du/dx, dv/dx), b = (du/dy, dv/dy)
// (Heckbert 1989, "Fundamentals of Texture Mapping and Image Warping", Sec. 3.5.5: the singular
// values of the Jacobian J = [a b]):
//   A = Px^2 + Py^2, E = Px^2 - Py^2, F = 2 a.b, D = a x b = du/dx dv/dy - dv/dx du/dy
//   Pmax'^2 = (A + H) / 2, H = sqrt(E^2 + F^2) (= sqrt(A^2 - 4 D^2)), Pmax' Pmin' = |D|
//   dot, cross       four 31 x 31-bit products of the clamped magnitudes, signed sums: |a.b|, |D|
//                    < 2^63, exact (Q.32)
//   H                hypot of |E| (63 bits) and |F| (64 bits): M = max, m = min, s = max(0,
//                    bit_width(M) - 16), M' = M >> s, m' = m >> s (16 bits, truncated), h =
//                    floor(sqrt(M'^2 + m'^2)) (33-bit radicand, 17-bit digit-by-digit root),
//                    H = M + ((h - M') << s) (65 bits); exact when E or F is 0; relative error
//                    below 2^-13
//   Pmax'^2          (A + min(H, A)) >> 1 (65-bit sum, floor; < 2^64 since H <= A in exact terms)
//   N                smallest n in 1..16 with n (8 + t) |D| >= 8 Pmax'^2 (Pmax'^2 / |D| = Pmax' /
//                    Pmin'; t = 0: n |D| >= Pmax'^2; 71-bit products, linear in n), 17 if none
//                    (|D| = 0 < Pmax'^2: a line), then min(., maxAniso) and the power-of-two
//                    rounding as above
//   lambda           lambda_from_length_sq(Pmax'^2, R[N]), the same unit and ROM
//   major axis       unchanged: the longer derivative vector carries the probes
// For axis-aligned derivatives (F = 0: du/dx du/dy = -dv/dx dv/dy, e.g. a = (du, 0), b = (0, dv))
// H = |E| exactly, Pmax'^2 = max(Px^2, Py^2), and n |D| >= Pmax'^2 is n^2 Pmin^2 >= Pmax^2: the
// ellipse axes give the screen axes' result bit for bit.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/datapath.hpp"
#include "cmodel/lod.hpp"

namespace tfu {

inline constexpr int kMaxAniso = 16;          // probes per pixel at most
inline constexpr int kProbeFracBits = 16;     // probe fraction q(N, i): Q.16, |q| < 2^15
inline constexpr int kAnisoWeightBits = 8;    // probe weights sum to 2^8
inline constexpr int kProbeRomAddrBits = 8;   // address {N - 1, i - 1}, 4 + 4 bits
inline constexpr int kAnisoThresholdBits = 3;  // aniso_threshold t: 0..7, in eighths of Pmin
inline constexpr int kAnisoThresholdMax = (1 << kAnisoThresholdBits) - 1;

// How the probe count is rounded (sampler-descriptor field aniso_rounding): any integer 1..maxAniso,
// or up to a power of two (1, 2, 4, 8, 16; the spec's "round N up to the nearest supported
// sampling rate").
enum class AnisoRounding { Integer, PowerOfTwo };

// Which axis lengths the LOD unit takes (sampler-descriptor field aniso_axes): the spec's Px, Py
// along the screen axes (Screen, the EXT text), or the true axes of the footprint ellipse
// (Ellipse: Pmax', Pmin' from the derivatives' dot and cross products; lambda does not depend on
// the ellipse's angle against the screen).
enum class AnisoAxes { Screen, Ellipse };

// The sampler-descriptor fields of anisotropic filtering (SamplerDescriptor::aniso() hands them to
// the LOD unit; a sampler without MIP-mapping gives max_aniso 1: it has no lambda to lower).
//
// aniso_threshold t (0..7) widens each probe's allowed footprint from Pmin to (1 + t/8) Pmin
// before the count grows: N = min(ceil(Pmax / ((1 + t/8) Pmin)), maxAniso). t = 0 is the spec's N
// bit for bit; a larger t spends fewer probes where the footprint is barely anisotropic (a
// real frame's Pmax / Pmin just above 1), at a probe footprint Pmax / N of at most (1 + t/8) Pmin,
// so lambda lies at most log2(1 + t/8) levels (0.91 for t = 7) above the spec's bound log2 Pmin.
// The idea of a sampler-descriptor threshold is AMD's (ANISO_THRESHOLD; Mesa ac_descriptors.c sets
// it to max_aniso_ratio >> 1); AMD does not document its meaning, this one is the model's own.
struct AnisoParams {
  int max_aniso = 1;  // maxAniso, 1..16 (1 = isotropic); values outside are clamped into 1..16
  AnisoRounding aniso_rounding = AnisoRounding::Integer;
  int aniso_threshold = 0;  // t, 0..7 (0: the spec's N); values outside are clamped into 0..7
  AnisoAxes aniso_axes = AnisoAxes::Screen;
};

// The anisotropic LOD unit's result for one pixel (or quad).
struct AnisoLod {
  uint64_t px2_q32 = 0;        // Px^2 = |du/dx|^2 + |dv/dx|^2, Q.32 level-0 texels^2 (clamped magnitudes)
  uint64_t py2_q32 = 0;        // Py^2, likewise from du/dy, dv/dy
  bool major_x = true;         // Px^2 >= Py^2: the probes step along the x derivative
  int64_t major_du_q16 = 0;    // the major derivative vector (du, dv), Q.16 level-0 texels,
  int64_t major_dv_q16 = 0;    //   magnitudes clamped to 2^31 - 1, signs kept
  int probes = 1;              // N, 1..16
  int32_t lambda_q8 = kLodMinusInfinity;  // log2(Pmax / N) in Q.8, before bias and clamp
  uint64_t pmax2_q32 = 0;      // the squared major length lambda is formed from: max(Px^2, Py^2)
                               //   (Screen) or the ellipse's Pmax'^2 (Ellipse), Q.32
  uint64_t det_q32 = 0;        // |D| = |a x b| = Pmax' Pmin', Q.32 (Ellipse; 0 with Screen)
};

// The LOD result of a request without derivatives (a lod-mode trace, textureLod) or of an
// isotropic sampler: one probe at the centre, the given lambda; Px, Py and the major vector 0.
constexpr AnisoLod isotropic_lod(int32_t lambda_q8) {
  AnisoLod a;
  a.lambda_q8 = lambda_q8;
  return a;
}

// The whole LOD unit: squared axis lengths, major axis, N and lambda.
AnisoLod aniso_lod(const TexelDerivatives& d, const AnisoParams& p);

// N from the squared axis lengths (pmin2 <= pmax2 expected; any pair is defined): smallest n in
// 1..16 with n^2 (8 + t)^2 pmin2 >= 64 pmax2 (t = aniso_threshold; t = 0: n^2 pmin2 >= pmax2; 17
// if none, e.g. pmin2 = 0 < pmax2), capped at max_aniso, then rounded up to a power of two with
// AnisoRounding::PowerOfTwo. pmax2 = pmin2 (also both 0) gives 1.
int aniso_probe_count(uint64_t pmax2_q32, uint64_t pmin2_q32, const AnisoParams& p);
// The threshold's scale (8 + t)^2 for t = aniso_threshold clamped into 0..7: 64, 81, ..., 225
// (an 8-entry x 8-bit table in the SV count unit).
constexpr uint32_t aniso_threshold_scale(int t) {
  const int c = 8 + (t < 0 ? 0 : t > kAnisoThresholdMax ? kAnisoThresholdMax : t);
  return static_cast<uint32_t>(c * c);
}

// The ellipse axes' parts (Ellipse mode; see the top of this file).
// The dot-and-cross unit: a.b and D = a x b of the clamped derivative vectors (magnitudes clamped
// to 2^31 - 1, signs kept), exact, Q.32 level-0 texels^2, |each| < 2^63.
struct DotCross {
  int64_t dot_q32 = 0;  // a.b = du/dx du/dy + dv/dx dv/dy
  int64_t det_q32 = 0;  // D = du/dx dv/dy - dv/dx du/dy
};
DotCross aniso_dot_cross(const TexelDerivatives& d);
// The hypot unit: H ~ sqrt(e^2 + f^2) from 16-bit mantissas, H = M + ((h - M') << s) as above;
// exact when e or f is 0; H >= max(e, f); H < 2^65 (returned in a 128-bit integer's low 65 bits).
__extension__ using AnisoU128 = unsigned __int128;
AnisoU128 aniso_hypot(uint64_t e, uint64_t f);
// Pmax'^2 = (A + min(H, A)) >> 1 from Px^2, Py^2 (each < 2^63) and a.b: A = Px^2 + Py^2, H =
// aniso_hypot(|Px^2 - Py^2|, 2 |a.b|). Q.32, <= A < 2^64.
uint64_t ellipse_major_len2(uint64_t px2_q32, uint64_t py2_q32, int64_t dot_q32);
// N from Pmax'^2 and |D|: smallest n in 1..16 with n (8 + t) |D| >= 8 Pmax'^2 (17 if none),
// capped at max_aniso, then rounded up to a power of two with AnisoRounding::PowerOfTwo.
// pmax2 = 0 (also with |D| = 0) gives 1; |D| = 0 < pmax2 gives maxAniso.
int aniso_probe_count_ellipse(uint64_t pmax2_q32, uint64_t det_q32, const AnisoParams& p);

// R[N - 1] = round(512 log2 N) = 256 log2(N^2) in Q.8, N = 1..16 (0, 512, 811, 1024, ...).
const std::array<int32_t, kMaxAniso>& aniso_log2_sq_rom();
// lambda = log2(Pmax / N) in Q.8: lambda_from_length_sq(pmax2, R[N - 1]); n in 1..16.
int32_t aniso_lambda(uint64_t pmax2_q32, int n);

// Exact floor(sqrt(x)), digit by digit: Px, Py in Q.16 level-0 texels from their squares
// (reporting, --query-lod), and the hypot unit's 17-bit root of a 33-bit radicand.
uint32_t axis_length_q16(uint64_t len2_q32);

// Probe ROM word for (N, i): the signed fraction q(N, i) = round-half-away(2^16 (2i - N - 1) /
// (2 (N + 1))) and the weight w(N, i). Weights: floor(256 / N) each, and the 256 mod N extra ones
// go one to the centre probe if N is odd and 256 mod N is odd, the rest in pairs to the innermost
// symmetric pairs; so w(N, i) = w(N, N + 1 - i) and sum_i w(N, i) = 256.
struct ProbeRomWord {
  int32_t frac_q16 = 0;  // |q| <= 28,913 (N = 16, i = 1 or 16): 15 bits + sign
  int32_t weight = 0;    // 1..256 (9 bits; 256 only for N = 1)
};
inline constexpr int probe_rom_address(int n, int i) { return ((n - 1) << 4) | (i - 1); }
// 256 words at {N - 1, i - 1}; words with i > N are zero (never addressed). Generated at compile
// time by make_probe_rom (exact integer arithmetic, the one source of the ROM contents).
using ProbeRom = std::array<ProbeRomWord, 1u << kProbeRomAddrBits>;
constexpr ProbeRom make_probe_rom() {
  ProbeRom r{};
  constexpr int kTotal = 1 << kAnisoWeightBits;
  const auto abs64 = [](int64_t x) { return x < 0 ? -x : x; };
  for (int n = 1; n <= kMaxAniso; ++n) {
    const int base = kTotal / n, extra = kTotal % n;
    const bool centre_extra = (n % 2 == 1) && (extra % 2 == 1);
    const int pairs = extra / 2;  // innermost symmetric pairs that get one more
    for (int i = 1; i <= n; ++i) {
      ProbeRomWord& w = r[static_cast<size_t>(probe_rom_address(n, i))];
      // q = 2^16 (2i - n - 1) / (2 (n + 1)), rounded half away from zero on the magnitude.
      const int64_t num = int64_t{2 * i - n - 1} * (int64_t{1} << kProbeFracBits), den = 2 * (n + 1);
      const int64_t mag = (2 * abs64(num) + den) / (2 * den);
      w.frac_q16 = static_cast<int32_t>(num < 0 ? -mag : mag);
      // Distance from the centre in half probe spacings: 0 (centre, n odd), 1, 2, 3, ...
      const auto k = static_cast<int>(abs64(2 * i - n - 1));
      const int ring = n % 2 == 1 ? k / 2 : (k + 1) / 2;  // 1 = innermost pair
      const bool plus = k == 0 ? centre_extra : ring <= pairs;
      w.weight = base + (plus ? 1 : 0);
    }
  }
  return r;
}
inline constexpr ProbeRom kProbeRom = make_probe_rom();
inline const ProbeRom& probe_rom() { return kProbeRom; }

// Offset of probe i (1..N) from the footprint centre along the major vector, per component:
// sgn(d) sgn(q) ((|d| |q(N, i)| + 2^15) >> 16), Q.16 level-0 texels, |result| < 2^30.
int64_t probe_offset_q16(int64_t major_q16, int n, int i);
struct ProbeOffset {
  int64_t du_q16 = 0, dv_q16 = 0;
};
ProbeOffset probe_offset(const AnisoLod& a, int i);

namespace dp {

// Probe offset unit, one component: sgn(d) sgn(q) ((|d| |q| + 2^15) >> 16) for the major
// derivative component d (Q.16, magnitude clamped to 2^31 - 1) and the probe ROM's fraction q
// (Q.16); a 31 x 15-bit product, |result| < 2^30.
inline int64_t scale_probe_fraction(int64_t major_q16, int32_t frac_q16) {
  const uint64_t m = uint64_t{derivative_magnitude(major_q16)} * static_cast<uint64_t>(frac_q16 < 0 ? -frac_q16 : frac_q16);
  const auto r = static_cast<int64_t>((m + (uint64_t{1} << (kProbeFracBits - 1))) >> kProbeFracBits);
  return (major_q16 < 0) != (frac_q16 < 0) ? -r : r;
}

// Address generator: a probe offset (Q.16 level-0 texels) on level L (0..15) in Q.8 texels of
// that level: sgn(o) ((|o| + 2^(7 + L)) >> (8 + L)) (round half away from zero; the level is taken
// as 2^L times smaller than level 0, exact for power-of-two textures).
inline int64_t probe_offset_on_level(int64_t offset_q16, int level) {
  const uint64_t m = offset_q16 < 0 ? uint64_t{0} - static_cast<uint64_t>(offset_q16) : static_cast<uint64_t>(offset_q16);
  const auto r = static_cast<int64_t>((m + (uint64_t{1} << (7 + level))) >> (8 + level));
  return offset_q16 < 0 ? -r : r;
}

// Probe coordinate on a level: the centre's Q.8 coordinate u = (i0 << 8) + f (texel_coord) plus the
// level offset, split again into the tap i0 = u >> 8 and the fraction f = u & 255.
inline LevelCoord probe_texel_coord(LevelCoord centre, int64_t offset_q8) {
  const int64_t u = centre.i0 * 256 + static_cast<int64_t>(centre.f) + offset_q8;
  return {u >> 8, static_cast<uint32_t>(u & 255)};
}

// NEAREST probe tap on a level: floor(s W_L + o / 256) for the probe offset o (Q.8 texels of the
// level), formed as the centre's tap floor(s W_L) (`centre_tap`, float_to_fixed with 0 fraction
// bits, as the isotropic NEAREST filter) plus the carry of the offset into the centre's subtexel
// position U & 255, U = floor(s W_L 2^8) = texel_coord's u + 128. An offset of 0 (N = 1, the centre
// probe of odd N) gives exactly the isotropic tap, also where the conversions saturate.
inline int64_t probe_nearest_tap(int64_t centre_tap, LevelCoord centre, int64_t offset_q8) {
  return centre_tap + ((static_cast<int64_t>((centre.f + 128u) & 255u) + offset_q8) >> 8);
}

// The probe accumulator register of the averaging unit: acc += w(N, i) c_i per channel as the
// probes of a pixel arrive (one per clock), then (acc + 128) >> 8. dp::aniso_average is this unit
// over an array; the cycle model's filter and edge_merge hold one.
struct AnisoAccumulator {
  std::array<int64_t, 4> acc{};
  void add(const Texel4& c, int n, int i);  // probe i (1..n) of n
  Texel4 result() const;                    // (acc + 128) >> 8 per channel
  void clear() { acc = {}; }
};

// Probe averaging unit: c = (sum_i w(N, i) c_i + 128) >> 8 per channel (round half up; an arithmetic
// shift for the signed VS16X2 channels). The weights sum to 256, so the result lies between the
// smallest and largest probe value of each channel (no clamp) and N = 1 is the identity.
// Widths: 8-bit channels 17 bits, VS16X2 (|c| <= 32,640) 24 bits signed. probes[0..n-1], n in 1..16.
Texel4 aniso_average(const Texel4* probes, int n);

}  // namespace dp
}  // namespace tfu
