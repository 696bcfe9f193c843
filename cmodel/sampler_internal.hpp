// Sampler internals shared by the golden datapath (sampler.cpp), its speed-only fast paths
// (sampler_fast.cpp) and the double-precision ideal path (sampler_ideal.cpp). Not a public header.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "cmodel/bspline_prefilter.hpp"
#include "cmodel/kernels.hpp"
#include "cmodel/sampler.hpp"

namespace tfu {
namespace detail {

// Memo of tile_weights_2d for nearest reconstruction: the weights depend only on the two ROM
// addresses, so the software model evaluates the multipliers once per address pair (a pure
// function: bit-identical to computing them per sample, which the tests check), and looks the
// addresses of the 8-bit fractions up in two tables.
struct WeightMemo {
  static constexpr size_t kStride = 16;  // weights per address pair
  int entries = 0;
  std::vector<int32_t> w;                  // [(addr_y * entries + addr_x) * kStride + tap]
  std::array<uint32_t, 256> col{}, row{};  // addr_x and addr_y * entries of each fraction
  const int32_t* weights(uint32_t fu, uint32_t fv) const { return w.data() + kStride * (row[fv] + col[fu]); }
};

}  // namespace detail

struct Sampler::Impl {
  std::unique_ptr<FilterKernel> kernel;              // CUBIC modes
  std::unique_ptr<TileWeightRom> rom;                // CUBIC modes
  bool prefiltered = false;                          // bspline-interp
  BsplineCoefficients coeffs;                        // bspline-interp: codes, exact values, S and B
  std::unique_ptr<detail::WeightMemo> memo;          // CUBIC with nearest reconstruction and R <= 128
  dp::CubicNormalize norm;                           // CUBIC normalise-and-clamp registers
  Texel4 border{};
  double scale = 255.0;  // channel code -> real
};

// The fast paths of sample() and sample_batch() (sampler_fast.cpp): one instantiation per variant.
struct Sampler::FastPaths {
  enum class Path { Linear8, Cubic8, Edge8 };
  struct Variant {  // what an instantiation is specialized for
    Path path;
    bool mipmapped;  // MipMode other than None
    WrapMode ws, wt;
  };
  template <Variant kV>
  static auto filter_at(const Sampler& sm, int level, dp::LevelCoord u, dp::LevelCoord v);
  template <Variant kV>
  static auto filter(const Sampler& sm, int level, float s, float t);
  // The level's result for the blend unit: Q.8 for LINEAR (dp::fast::Rgba8q), else filter_at's code.
  template <Variant kV>
  static auto filter_q8_at(const Sampler& sm, int level, dp::LevelCoord u, dp::LevelCoord v);
  template <Variant kV>
  static Rgba8 aniso(const Sampler& sm, float s, float t, const AnisoLod& lod);  // MIP-mapped variants, N > 1
  template <Variant kV>
  static Rgba8 sample(const Sampler& sm, float s, float t, int32_t lambda_q8);
  template <Variant kV>
  static void batch(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out);  // Linear8 only
  template <Path kP, bool kMip, size_t... k>
  static constexpr std::array<SampleFn, 16> wrap_table(std::index_sequence<k...>);
  template <bool kMip, size_t... k>
  static constexpr std::array<BatchFn, 16> batch_table(std::index_sequence<k...>);
  template <Path kP, size_t... k>
  static constexpr std::array<AnisoFn, 16> aniso_table(std::index_sequence<k...>);
  template <Path kP>
  static SampleFn pick(bool mipmapped, WrapMode ws, WrapMode wt);
  template <Path kP>
  static AnisoFn pick_aniso(bool mipmapped, WrapMode ws, WrapMode wt);
  // Chooses sample()'s path once the configuration is known: the fast path where one exists
  // (8-bit formats; for CUBIC also 4 x 4 taps and memoized weights), else the plain datapath;
  // and sample_batch()'s: LINEAR's batch variant where sample() has the LINEAR fast path, else a
  // loop over sample() (CUBIC and EDGE_PRESERVING spend 500+ instructions a sample, against some 20
  // for the call, so a per-variant batch copy of them would double their code for little).
  static void setup(Sampler& sm);
};

}  // namespace tfu
