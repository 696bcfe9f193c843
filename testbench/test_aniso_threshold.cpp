// The probe threshold of the anisotropic LOD unit (AnisoParams::aniso_threshold, docs/anisotropic.md
// "Probe threshold"): N = min(ceil(Pmax / ((1 + t/8) Pmin)), maxAniso). t = 0 is the spec's count
// bit for bit; exact ties k (1 + t/8) Pmin = Pmax at every t; random lengths against a long-double
// reference; hand values; the bound on the probe footprint; the descriptor field and sampler key.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "cmodel/aniso.hpp"
#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

__extension__ using u128 = unsigned __int128;

// The spec's N without a threshold, written from its definition: smallest k with k^2 Pmin^2 >= Pmax^2.
int spec_probe_count(uint64_t pmax2, uint64_t pmin2, int max_aniso) {
  int k = 1;
  while (k <= kMaxAniso && u128{static_cast<uint64_t>(k * k)} * pmin2 < pmax2) ++k;
  return std::min(k, max_aniso);
}

TEST(AnisoThreshold, ScaleTableIsEightPlusTSquared) {
  const uint32_t want[8] = {64, 81, 100, 121, 144, 169, 196, 225};
  for (int t = 0; t < 8; ++t) EXPECT_EQ(aniso_threshold_scale(t), want[t]) << t;
  EXPECT_EQ(aniso_threshold_scale(-3), 64u);  // clamped into 0..7
  EXPECT_EQ(aniso_threshold_scale(12), 225u);
}

TEST(AnisoThreshold, ZeroIsTheSpecsCountBitForBit) {
  std::mt19937_64 rng(34);
  const int n = test::iterations(400000);
  for (int i = 0; i < n; ++i) {
    // Lengths of every magnitude up to the unit's 63 bits; the ratio mostly within 1..20.
    const int shift = static_cast<int>(rng() % 62);
    const uint64_t pmin2 = (rng() >> (1 + shift)) + (i % 3 == 0 ? 0 : 1);
    const uint64_t r = 1 + rng() % 400;  // Pmax^2 / Pmin^2 near r: exact squares of integers, and one unit off
    uint64_t pmax2 = pmin2 > (uint64_t{1} << 62) / r ? pmin2 : pmin2 * r;
    const uint64_t off = rng() % 3;
    if (off == 1 && pmax2 > 0) --pmax2;
    if (off == 2) ++pmax2;
    for (int max_aniso : {1, 2, 7, 16}) {
      const AnisoParams p{max_aniso, AnisoRounding::Integer, 0};
      ASSERT_EQ(aniso_probe_count(std::max(pmax2, pmin2), std::min(pmax2, pmin2), p),
                spec_probe_count(std::max(pmax2, pmin2), std::min(pmax2, pmin2), max_aniso))
          << pmax2 << " " << pmin2 << " " << max_aniso;
    }
  }
}

// Pmin = 8m, Pmax = k (8 + t) m: the tie k (1 + t/8) Pmin = Pmax exactly gives N = k; one unit more
// of Pmax^2 gives k + 1.
TEST(AnisoThreshold, ExactTiesAtEveryThreshold) {
  for (int t = 0; t <= kAnisoThresholdMax; ++t)
    for (uint64_t m : {uint64_t{1}, uint64_t{3}, uint64_t{65536}, uint64_t{1000003}, uint64_t{1} << 22})  // Pmax^2 < 2^63
      for (int k = 1; k <= kMaxAniso; ++k) {
        const uint64_t pmin = 8 * m, pmax = static_cast<uint64_t>(k) * static_cast<uint64_t>(8 + t) * m;
        const AnisoParams p{16, AnisoRounding::Integer, t};
        EXPECT_EQ(aniso_probe_count(pmax * pmax, pmin * pmin, p), k) << t << " " << m << " " << k;
        EXPECT_EQ(aniso_probe_count(pmax * pmax + 1, pmin * pmin, p), std::min(k + 1, 16)) << t << " " << m << " " << k;
      }
}

TEST(AnisoThreshold, MatchesTheRealReferenceAwayFromTies) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ratio(1.0, 24.0), len(1.0, 1e5);  // Pmax^2 * 2^16 < 2^59
  const int n = test::iterations(200000);
  int checked = 0;
  for (int i = 0; i < n; ++i) {
    const double pmin = len(rng), r = ratio(rng);
    const auto pmin2 = static_cast<uint64_t>(pmin * pmin * 65536.0);
    const auto pmax2 = static_cast<uint64_t>(pmin * pmin * r * r * 65536.0);
    const int t = i % 8;
    const long double exact = std::sqrt(static_cast<long double>(pmax2) / static_cast<long double>(pmin2)) / (1.0L + t / 8.0L);
    if (std::fabs(exact - std::round(exact)) < 1e-9L) continue;  // ties: ExactTiesAtEveryThreshold
    for (int max_aniso : {2, 4, 16}) {
      const int want = std::min<int>(max_aniso, std::max(1, static_cast<int>(std::ceil(exact))));
      ASSERT_EQ(aniso_probe_count(pmax2, pmin2, {max_aniso, AnisoRounding::Integer, t}), want) << pmax2 << " " << pmin2 << " " << t;
      // Power-of-two rounding applies after the threshold.
      ASSERT_EQ(aniso_probe_count(pmax2, pmin2, {max_aniso, AnisoRounding::PowerOfTwo, t}),
                static_cast<int>(std::bit_ceil(static_cast<unsigned>(want))));
    }
    ++checked;
  }
  EXPECT_GT(checked, n * 9 / 10);
}

// Ratio 1.1 takes 2 probes by the spec and 1 from t = 1 (1.125) on; ratio 2.4 takes 3, 3, 2, ..., 2.
TEST(AnisoThreshold, HandValues) {
  const int want_11[8] = {2, 1, 1, 1, 1, 1, 1, 1};
  const int want_24[8] = {3, 3, 2, 2, 2, 2, 2, 2};  // 2.4 / 1.125 = 2.13; 2.4 / 1.25 = 1.92
  const int want_80[8] = {8, 8, 7, 6, 6, 5, 5, 5};  // ceil(64 / (8 + t)): 8, 7.11, 6.4, 5.82, 5.33, 4.92, 4.57, 4.27
  for (int t = 0; t < 8; ++t) {
    const AnisoParams p{16, AnisoRounding::Integer, t};
    EXPECT_EQ(aniso_probe_count(121, 100, p), want_11[t]) << t;
    EXPECT_EQ(aniso_probe_count(576, 100, p), want_24[t]) << t;
    EXPECT_EQ(aniso_probe_count(6400, 100, p), want_80[t]) << t;
    EXPECT_EQ(aniso_probe_count(100, 100, p), 1) << t;
    EXPECT_EQ(aniso_probe_count(100, 0, p), 16) << t;  // a line: maxAniso whatever t
    EXPECT_EQ(aniso_probe_count(0, 0, p), 1) << t;
  }
}

// The threshold never adds probes, and a probe's footprint Pmax / N stays within (1 + t/8) Pmin
// unless maxAniso caps N: lambda lies at most log2(1 + t/8) above the spec's bound log2 Pmin.
TEST(AnisoThreshold, FewerProbesAndTheFootprintBound) {
  std::mt19937_64 rng(11);
  const int n = test::iterations(100000);
  for (int i = 0; i < n; ++i) {
    const uint64_t pmin2 = 1 + (rng() >> (2 + rng() % 40));
    const uint64_t pmax2 = pmin2 * (1 + rng() % 300) + rng() % 1000;
    int prev = 17;
    for (int t = 0; t <= kAnisoThresholdMax; ++t) {
      const int got = aniso_probe_count(pmax2, pmin2, {16, AnisoRounding::Integer, t});
      ASSERT_LE(got, prev) << pmax2 << " " << pmin2 << " " << t;
      prev = got;
      if (got < 16) {  // N (8 + t) Pmin >= 8 Pmax, exactly
        ASSERT_GE(u128{static_cast<uint64_t>(got * got)} * aniso_threshold_scale(t) * pmin2, u128{pmax2} << 6);
      }
      if (got > 1) {  // and one probe fewer would not do
        ASSERT_LT(u128{static_cast<uint64_t>((got - 1) * (got - 1))} * aniso_threshold_scale(t) * pmin2, u128{pmax2} << 6);
      }
    }
  }
}

TEST(AnisoThreshold, DescriptorFieldAndSamplerKey) {
  SamplerDescriptor s;
  EXPECT_EQ(s.aniso_threshold, 0);  // the default is the spec's count
  s.mode = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
  s.max_aniso = 8;
  set_sampler_param(s, "aniso_threshold", "5");
  EXPECT_EQ(s.aniso_threshold, 5);
  EXPECT_EQ(s.aniso().aniso_threshold, 5);
  const auto words = encode(s);
  EXPECT_EQ((words[5] >> 5) & 7u, 5u);
  EXPECT_EQ(decode_sampler_descriptor(words), s);
  EXPECT_THROW(set_sampler_param(s, "aniso_threshold", "8"), InputError);
  EXPECT_THROW(set_sampler_param(s, "aniso_threshold", "-1"), InputError);
  s.aniso_threshold = 9;
  EXPECT_THROW(s.validate(), InputError);
}

}  // namespace
}  // namespace tfu
