#include "cmodel/edge_filter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>

namespace tfu::lee_jen {

namespace {

// Sort keys of the median network. The fixed-point datapath uses the integer key Y * 16 + n, which
// is unique, so one comparator decides; the ideal path pairs a real Y with the texel number.
struct RealKey {
  double y;
  int n;
};
constexpr bool before(int32_t a, int32_t b) { return a < b; }
constexpr bool before(const RealKey& a, const RealKey& b) { return a.y < b.y || (a.y == b.y && a.n < b.n); }
constexpr int texel_of(int32_t k) { return k & 15; }
constexpr int texel_of(const RealKey& k) { return k.n; }

// Compare cells (Lee & Jen Fig. 10): each outputs the smaller and the larger of its inputs.
template <typename K>
constexpr K cell_min(const K& a, const K& b) { return before(b, a) ? b : a; }
template <typename K>
constexpr K cell_max(const K& a, const K& b) { return before(b, a) ? a : b; }
// Three-point median: three cells. Five-point median: the four cells that drop the extremes of
// (a, b) and (c, d), then a three-point median with e.
template <typename K>
constexpr K median3(const K& a, const K& b, const K& c) { return cell_max(cell_min(a, b), cell_min(cell_max(a, b), c)); }
template <typename K>
constexpr K median5(const K& a, const K& b, const K& c, const K& d, const K& e) {
  return median3(e, cell_max(cell_min(a, b), cell_min(c, d)), cell_min(cell_max(a, b), cell_max(c, d)));
}

// Low-pass of Eq. 4 with the Sec. 3 adjustments: low[n] = number of the texel whose value is the
// median for Cn. Reads key[n] only for available texels; kAll: every texel is (the cross).
template <typename K, bool kAll = false>
std::array<int, kTexels + 1> low_pass(const std::array<K, kTexels + 1>& key, TexelMask available) {
  const auto k = [&](int n) -> const K& { return key[static_cast<size_t>(n)]; };
  const auto avail = [available](int n) { return kAll || has_texel(available, n); };
  std::array<int, kTexels + 1> low{};
  for (const BoundaryMedian& b : kBoundaryMedians)
    if (avail(b.self)) low[static_cast<size_t>(b.self)] = texel_of(median3(k(b.self), k(b.nb[0]), k(b.nb[1])));
  for (const CentreMedian& c : kCentreMedians) {
    const bool h1 = avail(c.outer[0]), h2 = avail(c.outer[1]);
    K m;
    if (h1 && h2) {
      m = median5(k(c.self), k(c.centre[0]), k(c.centre[1]), k(c.outer[0]), k(c.outer[1]));
    } else if (h1 || h2) {
      m = median5(k(c.self), k(c.centre[0]), k(c.centre[1]), k(h1 ? c.outer[0] : c.outer[1]), k(c.opposite));
    } else {
      m = median3(k(c.self), k(c.centre[0]), k(c.centre[1]));
    }
    low[static_cast<size_t>(c.self)] = texel_of(m);
  }
  return low;
}

// Per-direction constants gathered once: endpoints and blend axis, the usable-direction set of
// every 12-bit availability mask (the hardware decodes the kernel shape into these enables), and
// per ROM address the 22 weight codes side by side with the set of directions whose code is not
// "never choose".
struct DirectionTable {
  struct Entry {
    uint8_t p, q;  // endpoint texel numbers
    bool blend_x;  // t of Eq. 3 is fu (else fv)
  };
  std::array<Entry, kDirections> dir{};
  std::array<uint32_t, kAllTexels + 1> usable{};
  std::array<std::array<uint8_t, kDirections>, 256> weight{};  // [address][direction]
  std::array<uint32_t, 256> choosable{};                       // [address]: bit i = direction i
};

[[gnu::noinline]] DirectionTable build_direction_table() {
  DirectionTable d;
  for (const Direction& x : directions()) {
    const auto i = static_cast<size_t>(x.index);
    d.dir[i] = {static_cast<uint8_t>(x.p), static_cast<uint8_t>(x.q), x.axis == BlendAxis::X};
    const std::array<uint8_t, 256>& rom = direction_weight_rom(x.index);
    for (size_t a = 0; a < rom.size(); ++a) d.weight[a][i] = rom[a];
  }
  for (size_t a = 0; a < d.choosable.size(); ++a) d.choosable[a] = choosable_directions(a);
  for (uint32_t m = 0; m <= kAllTexels; ++m) d.usable[m] = usable_directions(static_cast<TexelMask>(m));
  return d;
}

inline const DirectionTable& direction_table() {
  static const DirectionTable t = build_direction_table();
  return t;
}

// Stage 3 for one family of formats. Each candidate direction's cost and index form the key
// cost * 32 + i, so the smallest key is the lowest cost with ties to the lowest index; only the
// usable, choosable directions are visited and the running minimum needs no branch.
template <bool kVs16>
EdgeDecision select_direction_keyed(const std::array<Texel4, kTexels>& c, const LowIndex& low, uint32_t usable,
                                    size_t addr) {
  constexpr TexelFormat kFmt = kVs16 ? TexelFormat::VS16X2 : TexelFormat::RGBA8;
  const DirectionTable& tab = direction_table();
  const std::array<uint8_t, kDirections>& w = tab.weight[addr];
  const auto lowv = [&](int n) -> const Texel4& { return c[static_cast<size_t>(low[static_cast<size_t>(n)] - 1)]; };
  static_assert(kDirections <= 32);
  constexpr uint64_t kNone = ~uint64_t{0};
  uint64_t best = kNone;
  for (uint32_t m = usable & tab.choosable[addr]; m != 0; m &= m - 1) {
    const auto i = static_cast<size_t>(std::countr_zero(m));
    const DirectionTable::Entry& e = tab.dir[i];
    const uint64_t cost = uint64_t{w[i]} * direction_difference(lowv(e.p), lowv(e.q), kFmt);
    const uint64_t key = (cost << 5) | i;
    best = key < best ? key : best;
  }
  if (best == kNone) return {0, 0, 0};  // unreachable: an axis direction through the centre square is always usable
  return {static_cast<int>(best & 31), static_cast<uint32_t>(best >> 5), 0};
}

}  // namespace

TexelMask cache_block_mask(int x4, int x5, int y4, int y8, int block) {
  // x / block and x % block as C++ defines them (quotient truncated toward zero, so a border
  // coordinate -1 is in block 0 with remainder -1). A tile side is a power of two: then the
  // quotient is a shift, with block - 1 added to a negative x first (software speed only; the
  // general form stays for any other block, and both are tested to agree).
  const bool pow2 = block > 0 && (block & (block - 1)) == 0;
  const int k = pow2 ? std::countr_zero(static_cast<unsigned>(block)) : 0;
  const auto quot = [pow2, k, block](int x) { return pow2 ? (x + ((x >> 31) & (block - 1))) >> k : x / block; };
  const auto rem = [pow2, k, block, &quot](int x) { return pow2 ? x - (quot(x) << k) : x % block; };
  // An arm is dropped when its texels lie in another block (selects, not branches: the shape
  // changes from pixel to pixel).
  const auto arm_if = [](Side s, bool dropped) { return static_cast<uint32_t>(arm(s).mask) * static_cast<uint32_t>(dropped); };
  const bool same_x = (x5 == x4 + 1) & (quot(x4) == quot(x5));
  const bool same_y = (y8 == y4 + 1) & (quot(y4) == quot(y8));
  const uint32_t dropped = arm_if(Side::Top, same_y & (rem(y4) == 0))             // top arm in the block above
                           | arm_if(Side::Bottom, same_y & (rem(y8) == block - 1))  // bottom arm in the block below
                           | arm_if(Side::Left, same_x & (rem(x4) == 0))            // left arm in the block to the left
                           | arm_if(Side::Right, same_x & (rem(x5) == block - 1));  // right arm in the block to the right
  return static_cast<TexelMask>(kAllTexels & ~dropped);
}

LumaKeys luma_keys(const std::array<Texel4, kTexels>& c, TexelMask available, TexelFormat fmt) {
  LumaKeys key{};
  for (int n = 1; n <= kTexels; ++n)
    if (has_texel(available, n)) key[static_cast<size_t>(n)] = edge_luma(c[static_cast<size_t>(n - 1)], fmt) * 16 + n;
  return key;
}

LowIndex median_low_pass(const LumaKeys& key, TexelMask available) {
  return (available & kAllTexels) == kAllTexels ? low_pass<int32_t, true>(key, available) : low_pass(key, available);
}

EdgeDecision select_direction(const std::array<Texel4, kTexels>& c, const LowIndex& low, TexelMask available,
                              uint32_t fu, uint32_t fv, TexelFormat fmt) {
  // Direction choice (Eq. 1-2): min w_i * dP_i over the usable directions, ties -> lowest index.
  const uint32_t usable = direction_table().usable[available & kAllTexels];
  const size_t addr = ((fv >> 4) << 4) | (fu >> 4);
  return fmt == TexelFormat::VS16X2 ? select_direction_keyed<true>(c, low, usable, addr)
                                    : select_direction_keyed<false>(c, low, usable, addr);
}

namespace {

// Stage 4 with the high-frequency sum in Acc: int32_t holds it exactly for 8-bit channels
// (|H| <= 255, the weights sum to 2^16), VS16X2 needs int64_t.
template <typename Acc>
Texel4 edge_merge_acc(const std::array<Texel4, kTexels>& c, const LowIndex& low, int direction, uint32_t fu,
                      uint32_t fv, int32_t lo, int32_t hi) {
  const auto lowv = [&](int n) -> const Texel4& { return c[static_cast<size_t>(low[static_cast<size_t>(n)] - 1)]; };
  // Low-frequency part along the chosen direction (Eq. 3).
  const DirectionTable::Entry& d = direction_table().dir[static_cast<size_t>(direction)];
  const int32_t t = static_cast<int32_t>(d.blend_x ? fu : fv);
  const Texel4& cp = lowv(d.p);
  const Texel4& cq = lowv(d.q);
  // High-frequency part, bilinear over H4, H5, H8, H9 (Eq. 5).
  const int32_t fx = static_cast<int32_t>(fu), fy = static_cast<int32_t>(fv);
  const std::array<Acc, 4> bw{(256 - fx) * (256 - fy), fx * (256 - fy), (256 - fx) * fy, fx * fy};
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    const int32_t clow = ((256 - t) * cp[ch] + t * cq[ch] + 128) >> 8;
    Acc hsum = 0;
    for (size_t k = 0; k < 4; ++k) {
      const int n = kCentreSquare[k];
      const int32_t h = c[static_cast<size_t>(n - 1)][ch] - lowv(n)[ch];
      hsum += Acc{h} * bw[k];
    }
    const auto chigh = static_cast<int32_t>((hsum + (1 << 15)) >> 16);
    out[ch] = std::clamp(clow + chigh, lo, hi);  // Eq. 6
  }
  return out;
}

}  // namespace

Texel4 edge_merge(const std::array<Texel4, kTexels>& c, const LowIndex& low, int direction, uint32_t fu, uint32_t fv,
                  TexelFormat fmt) {
  const auto [lo, hi] = channel_range(fmt);
  return fmt == TexelFormat::VS16X2 ? edge_merge_acc<int64_t>(c, low, direction, fu, fv, lo, hi)
                                    : edge_merge_acc<int32_t>(c, low, direction, fu, fv, lo, hi);
}

Texel4 edge_preserving_interpolate(const std::array<Texel4, kTexels>& c, TexelMask available, uint32_t fu, uint32_t fv,
                                   TexelFormat fmt, EdgeDecision* decision) {
  const LowIndex low = median_low_pass(luma_keys(c, available, fmt), available);
  EdgeDecision d = select_direction(c, low, available, fu, fv, fmt);
  d.read = static_cast<TexelMask>(available & kAllTexels);
  if (decision) *decision = d;
  return edge_merge(c, low, d.direction, fu, fv, fmt);
}

std::array<double, 4> edge_preserving_ideal(const std::array<std::array<double, 4>, kTexels>& c, TexelMask available,
                                            double fu, double fv, TexelFormat fmt) {
  std::array<RealKey, kTexels + 1> y{};
  for (int n = 1; n <= kTexels; ++n)
    if (has_texel(available, n)) {
      const auto& v = c[static_cast<size_t>(n - 1)];
      y[static_cast<size_t>(n)] = {fmt == TexelFormat::VS16X2 ? v[0] + v[1] : 0.3125 * v[0] + 0.5625 * v[1] + 0.125 * v[2], n};
    }
  const std::array<int, kTexels + 1> low = low_pass(y, available);
  const auto lowv = [&](int n) -> const std::array<double, 4>& {
    return c[static_cast<size_t>(low[static_cast<size_t>(n)] - 1)];
  };
  const uint32_t usable = usable_directions(available);
  int best = -1;
  double best_cost = 0;
  for (const Direction& d : directions()) {
    if (!((usable >> d.index) & 1u)) continue;
    const double w = exact_weight(d.index, fu, fv);
    if (!std::isfinite(w)) continue;
    const auto& p = lowv(d.p);
    const auto& q = lowv(d.q);
    const double dp = fmt == TexelFormat::VS16X2 ? std::abs(p[0] - q[0]) + std::abs(p[1] - q[1])
                                                 : std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
    if (best < 0 || w * dp < best_cost) {
      best = d.index;
      best_cost = w * dp;
    }
  }
  if (best < 0) best = 0;
  const Direction& d = directions()[static_cast<size_t>(best)];
  const double t = d.axis == BlendAxis::X ? fu : fv;
  const std::array<double, 4> bw{(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
  const double lo = fmt == TexelFormat::VS16X2 ? -1.0 : 0.0;
  std::array<double, 4> out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    double v = (1 - t) * lowv(d.p)[ch] + t * lowv(d.q)[ch];
    for (size_t k = 0; k < 4; ++k) v += bw[k] * (c[static_cast<size_t>(kCentreSquare[k] - 1)][ch] - lowv(kCentreSquare[k])[ch]);
    out[ch] = std::clamp(v, lo, 1.0);
  }
  return out;
}

}  // namespace tfu::lee_jen
