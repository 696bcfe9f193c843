// Speed-only forms of the cubic datapath's units (cmodel/datapath.hpp) on 8-bit texel words (RGBA8,
// L8 and B-spline coefficient codes: channels 0..255, decode_texel the identity), for the cycle
// model's CUBIC quad path (rtl/unit_recurrence_cubic_quads.cpp). Each equals its plain twin for
// every input (CubicFast.WordUnitsEqualTheChannelDatapath, CubicFast.WeightMemoEqualsTheWeightStage);
// the plain twins are the reference, what the golden model's plain path and the cycle model's
// filter block call and what the SystemVerilog implements:
//   cubic_accumulate8    dp::cubic_accumulate of the 16 words' channels
//   cubic_accumulate8_narrow   the same for weights below 2^15 in magnitude (SSE2 multiply-adds)
//   cubic_normalize8     dp::cubic_normalize to a result within 0..255, packed (encode_texel)
//   TileWeightMemo       dp::tile_weights_2d of one ROM, memoized per fraction pair
// Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain), which turns
// the whole CUBIC quad path off.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu::dp::fast {

// = dp::cubic_accumulate(decode_texel(c[k], RGBA8) ..., w, 16). Two channels per 64-bit word, (R, B)
// and (G, A) in 32-bit lanes (word_lanes_rb / word_lanes_ga): products wrap modulo 2^64, which
// keeps lo + hi 2^32 exact, and every channel's true sum is below 2^31 in magnitude (16 taps x 255
// x a weight of at most 2^16 - 1: < 2^28), so each lane's low 32 bits read as a signed number are
// that sum, and the borrow a negative low lane takes from the high one is added back. One row of
// taps per iteration (fully unrolled, the compiler spills the words' lanes).
[[gnu::always_inline]] inline std::array<int64_t, 4> cubic_accumulate8(const Rgba8* c, const int32_t* w) {
  uint64_t rb = 0, ga = 0;
#pragma GCC unroll 1
  for (size_t j = 0; j < 16; j += 4)
    for (size_t k = j; k < j + 4; ++k) {
      const auto wk = static_cast<uint64_t>(static_cast<int64_t>(w[k]));
      rb += word_lanes_rb(c[k]) * wk;
      ga += word_lanes_ga(c[k]) * wk;
    }
  const auto lo = [](uint64_t x) { return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>(x))); };
  const auto hi = [&lo](uint64_t x) {
    return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>((x - static_cast<uint64_t>(lo(x))) >> 32)));
  };
  return {lo(rb), lo(ga), hi(rb), hi(ga)};
}

// A weight of the 16-bit multiply-add (cubic_accumulate8_narrow): |w| < 2^15.
constexpr bool narrow_weight(int32_t w) { return w > -32768 && w < 32768; }

// cubic_accumulate8 for weights that are all narrow_weight (ROMs of up to 14 bits; TileWeightMemo
// tells): with SSE2 (every x86-64) the channels of two taps side by side in 16-bit lanes, (a.r, b.r,
// a.g, b.g, ...), against their weights (w_a, w_b) in each 32-bit lane, so one pmaddwd adds two
// taps' products per channel (|a w_a + b w_b| <= 2 x 255 x 2^15 < 2^31) and the sums stay below
// 2^27 in 32-bit lanes. Elsewhere cubic_accumulate8.
[[gnu::always_inline]] inline std::array<int64_t, 4> cubic_accumulate8_narrow(const Rgba8* c, const int32_t* w) {
#if defined(__SSE2__)
  const auto word = [c](size_t k) { return _mm_cvtsi32_si128(std::bit_cast<int32_t>(c[k])); };
  const auto weights = [w](size_t k) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(w + k)); };
  const __m128i w0 = _mm_packs_epi32(weights(0), weights(4)), w1 = _mm_packs_epi32(weights(8), weights(12));
  const __m128i zero = _mm_setzero_si128();
  __m128i acc = zero;
  // Row j's taps a, b, c, d (4 j .. 4 j + 3): (a, b) and (c, d) interleaved byte by byte, widened.
  const auto row = [&](size_t j, __m128i ab_weights, __m128i cd_weights) __attribute__((always_inline)) {
    const __m128i ac = _mm_unpacklo_epi32(word(4 * j), word(4 * j + 2)),
                  bd = _mm_unpacklo_epi32(word(4 * j + 1), word(4 * j + 3));
    const __m128i x = _mm_unpacklo_epi8(ac, bd);  // a.r b.r a.g b.g a.b b.b a.a b.a c.r d.r ...
    acc = _mm_add_epi32(acc, _mm_madd_epi16(_mm_unpacklo_epi8(x, zero), ab_weights));
    acc = _mm_add_epi32(acc, _mm_madd_epi16(_mm_unpackhi_epi8(x, zero), cd_weights));
  };
  row(0, _mm_shuffle_epi32(w0, 0x00), _mm_shuffle_epi32(w0, 0x55));
  row(1, _mm_shuffle_epi32(w0, 0xAA), _mm_shuffle_epi32(w0, 0xFF));
  row(2, _mm_shuffle_epi32(w1, 0x00), _mm_shuffle_epi32(w1, 0x55));
  row(3, _mm_shuffle_epi32(w1, 0xAA), _mm_shuffle_epi32(w1, 0xFF));
  return {_mm_cvtsi128_si32(acc), _mm_cvtsi128_si32(_mm_shuffle_epi32(acc, 0x55)),
          _mm_cvtsi128_si32(_mm_shuffle_epi32(acc, 0xAA)), _mm_cvtsi128_si32(_mm_shuffle_epi32(acc, 0xFF))};
#else
  return cubic_accumulate8(c, w);
#endif
}

// = encode_texel(dp::cubic_normalize(acc, n), f) for n's channel range 0..255 (RGBA8, L8, and
// the RGBA8 codes of B-spline coefficients: cubic_normalize_registers), so the pack clamps
// nothing. The default 8-bit ROM (M = 255, plain kernels): clamp(floor((2 acc + 255) / 510)); a
// negative numerator clamps to 0, so only non-negative ones are divided (truncation = floor).
[[gnu::always_inline]] inline Rgba8 cubic_normalize8(const std::array<int64_t, 4>& acc, const CubicNormalize& n) {
  if (n.M == 255 && !n.prefiltered) {
    const auto n8 = [](int64_t a) {
      const int64_t x = 2 * a + 255;
      return static_cast<uint8_t>(x < 0 ? 0 : (x / 510 > 255 ? 255 : x / 510));
    };
    return {n8(acc[0]), n8(acc[1]), n8(acc[2]), n8(acc[3])};
  }
  const Texel4 c = cubic_normalize(acc, n);  // within n.lo..n.hi = 0..255
  return {static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]),
          static_cast<uint8_t>(c[3])};
}

// dp::tile_weights_2d(rom, recon, fu, fv) of one 4-tap ROM, computed the first time a fraction pair
// (of a class, below) needs it and kept. The weight stage reads the ROM row of each fraction's
// address and multiplies the rows: with nearest reconstruction its output depends on fu and fv only
// through their addresses (rom.nearest_address), so fractions of one address share an entry; with
// linear reconstruction each fraction is its own class. The memo is software state, not hardware:
// the ROM and multipliers are a function of the sampler's registers and the fractions.
class TileWeightMemo {
 public:
  TileWeightMemo(const TileWeightRom& rom, RomRecon recon) : rom_(rom), recon_(recon) {
    // Classes numbered in order of their first fraction.
    std::vector<int> class_of(static_cast<size_t>(std::max(rom.entries(), 256)), -1);  // by address, or fraction
    for (uint32_t f = 0; f < 256; ++f) {
      const auto a = static_cast<size_t>(recon == RomRecon::Nearest ? rom.nearest_address(f, 8) : static_cast<int>(f));
      if (class_of[a] < 0) class_of[a] = static_cast<int>(classes_++);
      key_[f] = static_cast<uint16_t>(class_of[a]);
    }
    weights_ = std::make_unique_for_overwrite<std::array<int32_t, 16>[]>(classes_ * classes_);
    known_.assign(classes_ * classes_, 0);
  }
  // The 16 weights of (fu, fv), row-major (tap (i, j) at 4 j + i), as dp::tile_weights_2d writes
  // them; `narrow`: every one is narrow_weight.
  [[gnu::always_inline]] const int32_t* weights(uint32_t fu, uint32_t fv, bool& narrow) {
    const size_t e = key_[fv] * classes_ + key_[fu];
    if (known_[e] == 0) [[unlikely]]
      fill(e, fu, fv);
    narrow = known_[e] == kNarrow;
    return weights_[e].data();
  }

 private:
  const TileWeightRom& rom_;
  RomRecon recon_;
  std::array<uint16_t, 256> key_{};  // the class of each 8-bit fraction
  size_t classes_ = 0;
  std::unique_ptr<std::array<int32_t, 16>[]> weights_;  // [key(fv) classes + key(fu)], written on first use
  static constexpr uint8_t kNarrow = 1, kWide = 2;
  std::vector<uint8_t> known_;  // per entry: 0 not yet computed, kNarrow, kWide
  void fill(size_t e, uint32_t fu, uint32_t fv) {
    tile_weights_2d(rom_, recon_, fu, fv, weights_[e]);
    known_[e] = std::all_of(weights_[e].begin(), weights_[e].end(), narrow_weight) ? kNarrow : kWide;
  }
};

}  // namespace tfu::dp::fast
