// Speed-only forms of the cubic datapath's units (cmodel/datapath.hpp) on 8-bit texel words (RGBA8,
// L8 and B-spline coefficient codes: channels 0..255, decode_texel the identity), for the cycle
// model's CUBIC quad path (rtl/unit_recurrence_cubic_quads.cpp). Each equals its plain twin for
// every input (CubicFast.WordUnitsEqualTheChannelDatapath, CubicFast.WeightMemoEqualsTheWeightStage);
// the plain twins are the reference, what the golden model's plain path and the cycle model's
// filter block call and what the SystemVerilog implements:
//   cubic_accumulate8    dp::cubic_accumulate of the 16 words' channels
//   cubic_normalize8     dp::cubic_normalize to a result within 0..255, packed (encode_texel)
//   TileWeightMemo       dp::tile_weights_2d of one ROM, memoized per fraction pair
// Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain), which turns
// the whole CUBIC quad path off.
#pragma once

#include <algorithm>
#include <array>
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
// that sum, and the borrow a negative low lane takes from the high one is added back.
[[gnu::always_inline]] inline std::array<int64_t, 4> cubic_accumulate8(const Rgba8* c, const int32_t* w) {
  uint64_t rb = 0, ga = 0;
  for (size_t k = 0; k < 16; ++k) {
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
  return {static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]), static_cast<uint8_t>(c[3])};
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
  // The 16 weights of (fu, fv), row-major (tap (i, j) at 4 j + i), as dp::tile_weights_2d writes them.
  [[gnu::always_inline]] const int32_t* weights(uint32_t fu, uint32_t fv) {
    const size_t e = key_[fv] * classes_ + key_[fu];
    if (!known_[e]) [[unlikely]]
      fill(e, fu, fv);
    return weights_[e].data();
  }

 private:
  const TileWeightRom& rom_;
  RomRecon recon_;
  std::array<uint16_t, 256> key_{};  // the class of each 8-bit fraction
  size_t classes_ = 0;
  std::unique_ptr<std::array<int32_t, 16>[]> weights_;  // [key(fv) classes + key(fu)], written on first use
  std::vector<uint8_t> known_;
  void fill(size_t e, uint32_t fu, uint32_t fv) {
    tile_weights_2d(rom_, recon_, fu, fv, weights_[e]);
    known_[e] = 1;
  }
};

}  // namespace tfu::dp::fast
