#include "cmodel/weight_rom.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cmodel/error.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

void TileRomSpec::validate() const {
  if (samples < kMinSamples || samples > kMaxSamples)
    throw InputError("samples per tile R=" + std::to_string(samples) + " out of range [" +
                     std::to_string(kMinSamples) + ", " + std::to_string(kMaxSamples) + "]");
  if (bits < kMinBits || bits > kMaxBits)
    throw InputError("ROM word bits b=" + std::to_string(bits) + " out of range [" + std::to_string(kMinBits) +
                     ", " + std::to_string(kMaxBits) + "]");
}

RomWord quantize_weight(double w, unsigned bits) {
  RomWord q;
  q.mag = unorm::encode_round(std::abs(w), bits);
  q.neg = w < 0.0 && q.mag != 0;
  return q;
}

namespace {

// Largest-remainder rounding of a row of signed weights (scaled to codes) so that the integer
// codes sum to round(sum of the scaled values). Ties are broken towards the tap nearer the
// row's centre, then the lower tap, so rows that are mirror images round as mirror images
// except for exact ties between mirror taps.
void round_row_sum_preserving(const double* scaled, int n, int32_t* out) {
  double total = 0.0;
  std::vector<double> rem(static_cast<size_t>(n));
  int64_t floor_sum = 0;
  for (int i = 0; i < n; ++i) {
    const double fl = std::floor(scaled[i]);
    out[i] = static_cast<int32_t>(fl);
    rem[static_cast<size_t>(i)] = scaled[i] - fl;
    floor_sum += out[i];
    total += scaled[i];
  }
  const int64_t target = static_cast<int64_t>(std::llround(total));
  int64_t need = target - floor_sum;  // number of entries to round up, 0 <= need <= n
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  const double centre = (n - 1) / 2.0;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double ra = rem[static_cast<size_t>(a)], rb = rem[static_cast<size_t>(b)];
    if (std::abs(ra - rb) > 1e-12) return ra > rb;
    return std::abs(a - centre) < std::abs(b - centre);
  });
  for (int i = 0; i < n && need > 0; ++i, --need) out[order[static_cast<size_t>(i)]] += 1;
}

}  // namespace

TileWeightRom::TileWeightRom(const FilterKernel& kernel, TileRomSpec spec)
    : spec_(spec), kernel_name_(kernel.name()), taps_(2 * ((kernel.width() + 1) / 2)) {
  spec_.validate();
  const int n = spec_.entries();
  words_.resize(static_cast<size_t>(n) * taps_);
  exact_.resize(words_.size());
  const double scale = static_cast<double>(unorm::max_code(spec_.bits));
  std::vector<double> scaled(static_cast<size_t>(taps_));
  std::vector<int32_t> codes(static_cast<size_t>(taps_));
  for (int k = 0; k < n; ++k) {
    const double f = spec_.position(k);
    for (int t = 0; t < taps_; ++t) {
      const int m = first_tap() + t;
      const double w = kernel(f - m);
      exact_[static_cast<size_t>(k) * taps_ + t] = w;
      scaled[static_cast<size_t>(t)] = w * scale;
    }
    if (spec_.rounding == RomRounding::SumPreserving) {
      round_row_sum_preserving(scaled.data(), taps_, codes.data());
      for (int t = 0; t < taps_; ++t) {
        const int32_t c = std::clamp<int32_t>(codes[static_cast<size_t>(t)], -static_cast<int32_t>(scale),
                                              static_cast<int32_t>(scale));
        words_[static_cast<size_t>(k) * taps_ + t] = RomWord{static_cast<uint32_t>(std::abs(c)), c < 0};
      }
    } else {
      for (int t = 0; t < taps_; ++t)
        words_[static_cast<size_t>(k) * taps_ + t] =
            quantize_weight(exact_[static_cast<size_t>(k) * taps_ + t], spec_.bits);
    }
  }
}

int TileWeightRom::nearest_address(uint32_t f, unsigned fbits) const {
  const uint64_t R = static_cast<uint64_t>(spec_.samples);
  if (spec_.pos == SamplePos::Centre) {
    const uint64_t a = (uint64_t{f} * R) >> fbits;  // floor(f * R)
    return static_cast<int>(std::min<uint64_t>(a, R - 1));
  }
  const uint64_t a = (uint64_t{f} * R + (uint64_t{1} << fbits >> 1)) >> fbits;  // floor(f * R + 1/2)
  return static_cast<int>(std::min<uint64_t>(a, R));
}

void TileWeightRom::weights_nearest(uint32_t f, unsigned fbits, int32_t* out) const {
  const auto r = row(nearest_address(f, fbits));
  for (int t = 0; t < taps_; ++t) out[t] = r[static_cast<size_t>(t)].value();
}

void TileWeightRom::weights_linear(uint32_t f, unsigned fbits, unsigned abits, int32_t* out) const {
  // Position in entry units, with `abits` fraction bits: u = f * R (- 1/2 for centre sampling).
  const int64_t R = spec_.samples;
  const int64_t one = int64_t{1} << abits;
  // f * R in abits fixed point, rounded down.
  int64_t u = (static_cast<int64_t>(f) * R * one) >> fbits;
  if (spec_.pos == SamplePos::Centre) u -= one / 2;
  const int64_t last = spec_.entries() - 1;
  int64_t k0 = u >> abits;  // floor (arithmetic shift on negative u)
  int64_t alpha = u & (one - 1);
  if (k0 < 0) { k0 = 0; alpha = 0; }
  if (k0 >= last) { k0 = last; alpha = 0; }
  const int64_t k1 = std::min(k0 + 1, last);
  const auto r0 = row(static_cast<int>(k0));
  const auto r1 = row(static_cast<int>(k1));
  for (int t = 0; t < taps_; ++t) {
    const int64_t q0 = r0[static_cast<size_t>(t)].value(), q1 = r1[static_cast<size_t>(t)].value();
    out[t] = static_cast<int32_t>((q0 * (one - alpha) + q1 * alpha + one / 2) >> abits);
  }
}


// ---------------------------------------------------------------------------------------------
TileWeightRom2D::TileWeightRom2D(const FilterKernel& kernel, TileRomSpec spec)
    : spec_(spec), kernel_(kernel), taps_(2 * ((kernel.width() + 1) / 2)) {
  spec_.validate();
  const int half = taps_ / 2;
  for (int cy = 0; cy < half; ++cy)
    for (int cx = 0; cx <= cy; ++cx) {
      stored_index_.emplace_back(cx, cy);
      const int n = spec_.entries();
      std::vector<RomWord> tile(static_cast<size_t>(n) * n);
      for (int ky = 0; ky < n; ++ky)
        for (int kx = 0; kx < n; ++kx) tile[static_cast<size_t>(ky) * n + kx] = word_direct(cx, cy, kx, ky);
      stored_.push_back(std::move(tile));
    }
}

RomWord TileWeightRom2D::word_direct(int tx, int ty, int kx, int ky) const {
  // Tile j covers [j - T/2, j - T/2 + 1].
  const double x = tx - taps_ / 2 + spec_.position(kx);
  const double y = ty - taps_ / 2 + spec_.position(ky);
  return quantize_weight(kernel_(x) * kernel_(y), spec_.bits);
}

int TileWeightRom2D::stored_slot(int ctx, int cty) const {
  for (size_t i = 0; i < stored_index_.size(); ++i)
    if (stored_index_[i] == std::pair<int, int>{ctx, cty}) return static_cast<int>(i);
  return -1;
}

RomWord TileWeightRom2D::word(int tx, int ty, int kx, int ky) const {
  const int half = taps_ / 2;
  const int last = spec_.entries() - 1;
  // Mirror (h even): tile j at local u equals tile T-1-j at local 1-u.
  auto mirror = [&](int& t, int& k) {
    if (t >= half) {
      t = taps_ - 1 - t;
      k = spec_.pos == SamplePos::Centre ? last - k : spec_.samples - k;
    }
  };
  mirror(tx, kx);
  mirror(ty, ky);
  if (tx > ty) {  // h(x)h(y) == h(y)h(x): swap axes
    std::swap(tx, ty);
    std::swap(kx, ky);
  }
  const int n = spec_.entries();
  return stored_[static_cast<size_t>(stored_slot(tx, ty))][static_cast<size_t>(ky) * n + kx];
}

}  // namespace tfu
