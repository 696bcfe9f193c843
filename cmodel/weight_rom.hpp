// Tiled high-resolution filter-weight ROMs (Hadwiger et al. 2002 Sec. 2; Hadwiger 2004 Sec. 3.1).
//
// A kernel h of support width W is cut into T = 2*ceil(W/2) unit tiles; tile j covers
// [j - T/2, j - T/2 + 1]. Each tile is sampled at R positions (R = 16..512) and quantized to b bits.
// For a fractional resampling position f in [0, 1) the filter needs one weight per tap
// m = -(T/2 - 1) .. T/2 (texel offset relative to the texel left of the sample point), namely
// h(f - m), which lies in tile j = T/2 - m at the SAME local position f. Hence one ROM address
// (derived from f) yields all T weights: the interleaved "RGBA" layout of dissertation Fig. 3.10.
//
// Sampling positions inside a tile (documented choice, see docs/number-formats.md):
//   SamplePos::Centre : entry k holds h at local position (k + 0.5) / R   (R entries, GL texel centres)
//   SamplePos::Corner : entry k holds h at local position k / R            (R + 1 entries)
//
// Negative weights: sign + magnitude. Each ROM word is a b-bit magnitude code (1.0 <-> 2^b - 1,
// unorm of unorm.hpp) plus one sign bit, so a word is b + 1 bits wide. The tile-weight multiplier
// multiplies magnitudes with the normalized multiplier and XORs the signs.
//
// Quantization of a ROM row (the T weights at one address):
//   RomRounding::Nearest       : each magnitude rounded by Eq. 3.4 independently (what Table 3.5
//                                of the dissertation analyses);
//   RomRounding::SumPreserving : largest-remainder rounding of the signed values so that the T
//                                codes of every row sum to exactly 2^b - 1 whenever the exact
//                                weights sum to 1 (partition of unity survives quantization, so
//                                a constant texture is reproduced exactly). Each code still differs
//                                from the exact value by less than 1 LSB. This is the default for
//                                the filter datapath.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cmodel/kernels.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

enum class SamplePos { Centre, Corner };
enum class RomRounding { Nearest, SumPreserving };
enum class RomRecon { Nearest, Linear };

// One ROM word: sign + b-bit magnitude. value() is the signed code at scale 2^b - 1.
struct RomWord {
  uint32_t mag = 0;
  bool neg = false;
  constexpr int32_t value() const { return neg ? -static_cast<int32_t>(mag) : static_cast<int32_t>(mag); }
  friend constexpr bool operator==(const RomWord&, const RomWord&) = default;
};

struct TileRomSpec {
  int samples = 64;        // R: samples per tile and dimension, 16..512
  unsigned bits = 8;       // b: magnitude bits, 4..16
  SamplePos pos = SamplePos::Centre;
  RomRounding rounding = RomRounding::SumPreserving;

  static constexpr int kMinSamples = 16, kMaxSamples = 512;
  static constexpr unsigned kMinBits = 4, kMaxBits = 16;
  void validate() const;  // throws InputError naming the bad field
  friend constexpr bool operator==(const TileRomSpec&, const TileRomSpec&) = default;
  int entries() const { return pos == SamplePos::Centre ? samples : samples + 1; }
  // Local position (in [0, 1]) that entry k samples.
  double position(int k) const {
    return pos == SamplePos::Centre ? (k + 0.5) / samples : static_cast<double>(k) / samples;
  }
};

// Quantize a signed real weight to a sign-magnitude word by Eq. 3.4 (magnitudes saturate at 1.0).
RomWord quantize_weight(double w, unsigned bits);

// 1D tiled weight ROM in the interleaved layout: row(addr) returns the T taps for one address.
class TileWeightRom {
 public:
  TileWeightRom(const FilterKernel& kernel, TileRomSpec spec);

  const TileRomSpec& spec() const { return spec_; }
  const std::string& kernel_name() const { return kernel_name_; }
  int taps() const { return taps_; }           // T (= number of tiles)
  int first_tap() const { return 1 - taps_ / 2; }  // texel offset m of tap 0
  int entries() const { return spec_.entries(); }
  // Interleaved layout (Fig. 3.10): the T words for address k, ordered by tap (texel offset).
  std::span<const RomWord> row(int addr) const {
    return {words_.data() + static_cast<size_t>(addr) * taps_, static_cast<size_t>(taps_)};
  }
  // "One 1D ROM per tile" layout: word k of tile j (tile j holds tap T/2 - m, see header).
  RomWord tile_word(int tile, int addr) const { return row(addr)[static_cast<size_t>(taps_ - 1 - tile)]; }
  // Exact (double) weight that ROM entry (addr, tap) approximates.
  double exact(int addr, int tap) const { return exact_[static_cast<size_t>(addr) * taps_ + tap]; }

  // ---- Reconstruction as the datapath does it (integer, bit-exact) ----
  // The fraction f arrives as an unsigned fixed-point number with `fbits` fraction bits.
  // Nearest: address floor(f * R) for centre sampling, floor(f * R + 1/2) for corner sampling.
  int nearest_address(uint32_t f, unsigned fbits) const;
  void weights_nearest(uint32_t f, unsigned fbits, int32_t* out) const;
  // Linear: GL_LINEAR between the two entries that bracket f (clamped to the tile's first/last
  // entry), blend factor alpha with `abits` bits: w = (q0 (2^a - alpha) + q1 alpha + 2^(a-1)) >> a
  // (arithmetic shift, i.e. round half up, on signed values).
  void weights_linear(uint32_t f, unsigned fbits, unsigned abits, int32_t* out) const;

 private:
  TileRomSpec spec_;
  std::string kernel_name_;
  int taps_;
  std::vector<RomWord> words_;  // entries() * taps_, interleaved
  std::vector<double> exact_;   // same layout, exact kernel values
};

// Separable composition through the tile-weight multiplier (Hadwiger 2002 Sec. 2):
// w(x, y) = wx * wy with magnitudes multiplied by the b-bit normalized multiplier with rounding
// (unorm::mul_round == the division-free hardware form) and signs XORed. Result is at scale 2^b - 1.
inline int32_t tile_weight_multiply(int32_t wx, int32_t wy, unsigned bits) {
  const uint32_t mag = unorm::mul_divfree(static_cast<uint32_t>(wx < 0 ? -wx : wx), static_cast<uint32_t>(wy < 0 ? -wy : wy), bits);
  const bool neg = (wx < 0) != (wy < 0);
  return neg ? -static_cast<int32_t>(mag) : static_cast<int32_t>(mag);
}

// Non-separable 2D tiles: T x T tiles of R x R words, entry (kx, ky) of tile (tx, ty) holds
// quantize_weight(h(x) h(y)) (Eq. 3.4 rounding). Symmetric storage keeps only the tiles with
// canonical index (mirror each axis onto tiles 0..T/2-1, then order the pair): 3 for a bicubic
// instead of 16. Reads of other tiles mirror the address and/or swap x and y.
class TileWeightRom2D {
 public:
  TileWeightRom2D(const FilterKernel& kernel, TileRomSpec spec);
  int taps() const { return taps_; }
  int stored_tiles() const { return static_cast<int>(stored_.size()); }
  int full_tiles() const { return taps_ * taps_; }
  // Word of tile (tx, ty) at entry (kx, ky), read through the symmetric storage.
  RomWord word(int tx, int ty, int kx, int ky) const;
  // The same word generated directly (no symmetry), for verification.
  RomWord word_direct(int tx, int ty, int kx, int ky) const;

 private:
  TileRomSpec spec_;
  FilterKernel kernel_;
  int taps_;
  std::vector<std::pair<int, int>> stored_index_;  // canonical (tx, ty) of each stored tile
  std::vector<std::vector<RomWord>> stored_;       // R x R words each (row-major by ky)
  int stored_slot(int ctx, int cty) const;
};

}  // namespace tfu
