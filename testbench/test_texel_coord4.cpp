// The 4-lane address stage of the sampler's batch (cmodel/texel_coord4.hpp) against its plain
// twins: dp::texel_coord (float_to_fixed_fast) per lane, dp::fast::wrap_taps<kW, 2> per lane
// (wrap_index for repeat's remainder unit), and y w. SSE2 only (the unit does not exist elsewhere).
#if defined(__SSE2__)
#include <gtest/gtest.h>
#include <xmmintrin.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/texel_coord4.hpp"
#include "testbench/fp_environment.hpp"

namespace tfu {
namespace {

using test::FpEnvironment;

// Extents: every power of two 1..2^15, the odd and largest ones, and random ones.
std::vector<int> extents(std::mt19937& rng) {
  std::vector<int> e;
  for (int k = 0; k <= 15; ++k) e.push_back(1 << k);
  for (int x : {3, 5, 7, 37, 255, 1000, 1023, 1025, 4095, 32767}) e.push_back(x);
  std::uniform_int_distribution<int> any(1, 32768);
  for (int k = 0; k < 8; ++k) e.push_back(any(rng));
  return e;
}

// Whether the unit is meant to take x: zero, or normal with exponent field <= 141.
bool taken(float x) {
  const uint32_t a = std::bit_cast<uint32_t>(x) & 0x7FFFFFFFu;
  return a == 0 || (a >= 0x00800000u && a < (142u << 23));
}

// Runs the unit on four values and compares every lane it takes with dp::texel_coord; counts lanes.
void check4(const std::array<float, 4>& x, int size, size_t& compared) {
  const __m128 v = _mm_setr_ps(x[0], x[1], x[2], x[3]);
  const int lanes = dp::fast::texel_coord4_lanes(v);
  const dp::fast::TexelCoords4 c = dp::fast::texel_coord4(dp::fast::widen4(v), size);
  alignas(16) std::array<int32_t, 4> i0{}, f{};
  _mm_store_si128(reinterpret_cast<__m128i*>(i0.data()), c.i0);
  _mm_store_si128(reinterpret_cast<__m128i*>(f.data()), c.f);
  for (size_t k = 0; k < 4; ++k) {
    ASSERT_EQ((lanes >> k & 1) != 0, taken(x[k])) << std::hex << std::bit_cast<uint32_t>(x[k]);
    if (!taken(x[k])) continue;
    const dp::LevelCoord p = dp::texel_coord(x[k], size);
    ASSERT_EQ(int64_t{i0[k]}, p.i0) << std::hex << std::bit_cast<uint32_t>(x[k]) << std::dec << " size " << size;
    ASSERT_EQ(static_cast<uint32_t>(f[k]), p.f) << std::hex << std::bit_cast<uint32_t>(x[k]) << std::dec << " size " << size;
    ++compared;
  }
}

// Every exponent field 0..255, both signs, the boundary mantissas (0, 1, half, all ones) and random
// ones, on every extent of extents(): NaN, infinities, denormals, zeros and huge values are among
// them (exponents 0 and 255, and >= 142, which the unit must leave to the plain unit); also under
// every IEEE rounding mode and with MXCSR's flush-to-zero and denormals-are-zero set.
TEST(TexelCoord4, EqualsTexelCoordOnEveryExponent) {
  std::mt19937 rng(41);
  std::uniform_int_distribution<uint32_t> mant(0, 0x7FFFFF);
  const std::vector<int> sizes = extents(rng);
  size_t compared = 0, left = 0;
  for (int mode = 0; mode < FpEnvironment::kCount; ++mode) {
    const FpEnvironment env(mode);
    ASSERT_TRUE(env.set()) << mode;
    const int per = mode == 0 ? 64 : 8;  // random mantissas per (exponent, sign) and extent
    for (uint32_t exp = 0; exp < 256; ++exp)
      for (uint32_t sign = 0; sign < 2; ++sign)
        for (int size : sizes) {
          std::vector<float> xs;
          for (uint32_t m : {0u, 1u, 0x400000u, 0x7FFFFFu, 0x7FFFFEu}) xs.push_back(std::bit_cast<float>(sign << 31 | exp << 23 | m));
          for (int k = 0; k < per; ++k) xs.push_back(std::bit_cast<float>(sign << 31 | exp << 23 | mant(rng)));
          while (xs.size() % 4 != 0) xs.push_back(0.5f);
          for (size_t i = 0; i < xs.size(); i += 4) {
            check4({xs[i], xs[i + 1], xs[i + 2], xs[i + 3]}, size, compared);
            if (HasFatalFailure()) return;
            for (size_t k = 0; k < 4; ++k) left += !taken(xs[i + k]);
          }
        }
  }
  // Coordinates of texture space: every float in [-4, 4) of some exponents, lanes in every order.
  for (int size : {1, 16, 37, 1024, 32768})
    for (uint32_t b = std::bit_cast<uint32_t>(1.0f); b < std::bit_cast<uint32_t>(1.0f) + 4096; b += 4) {
      const float x = std::bit_cast<float>(b);
      check4({x, -x, x * 3.0f, -x * 0.75f}, size, compared);
      ASSERT_FALSE(HasFatalFailure());
    }
  EXPECT_GT(compared, 1'000'000u);
  EXPECT_GT(left, 100'000u);  // the lanes left to the plain unit were seen
}

// The binary32 coordinate unit on power-of-two extents (texel_coord4_pow2) against dp::texel_coord:
// runs on four lanes the unit takes and must take them exactly when every |x| W 2^8 < 2^30 (else
// the caller uses texel_coord4, compared above). Every extent 2^0..2^15, every exponent and sign
// with boundary and random mantissas, the values next to the 2^30 limit, and a sweep of every
// 4093rd float bit pattern; under the four rounding modes and with FTZ and DAZ.
void check4_pow2(const std::array<float, 4>& x, int size, size_t& compared, size_t& declined) {
  for (float v : x)
    if (!taken(v)) return;  // the batch's caller never passes such a group here
  const __m128 v = _mm_setr_ps(x[0], x[1], x[2], x[3]);
  bool inside = true;
  for (float e : x) inside &= std::abs(static_cast<double>(e) * size * 256.0) < 0x1p30;
  dp::fast::TexelCoords4 c{};
  const bool took = dp::fast::texel_coord4_pow2(v, size, c);
  ASSERT_EQ(took, inside) << x[0] << ' ' << x[1] << ' ' << x[2] << ' ' << x[3] << " size " << size;
  if (!took) {
    ++declined;
    return;
  }
  alignas(16) std::array<int32_t, 4> i0{}, f{};
  _mm_store_si128(reinterpret_cast<__m128i*>(i0.data()), c.i0);
  _mm_store_si128(reinterpret_cast<__m128i*>(f.data()), c.f);
  for (size_t k = 0; k < 4; ++k) {
    const dp::LevelCoord p = dp::texel_coord(x[k], size);
    ASSERT_EQ(int64_t{i0[k]}, p.i0) << std::hex << std::bit_cast<uint32_t>(x[k]) << std::dec << " size " << size;
    ASSERT_EQ(static_cast<uint32_t>(f[k]), p.f) << std::hex << std::bit_cast<uint32_t>(x[k]) << std::dec << " size " << size;
    ++compared;
  }
}

TEST(TexelCoord4, Pow2EqualsTexelCoord) {
  std::mt19937 rng(43);
  std::uniform_int_distribution<uint32_t> mant(0, 0x7FFFFF);
  size_t compared = 0, declined = 0;
  for (int mode = 0; mode < FpEnvironment::kCount; ++mode) {
    const FpEnvironment env(mode);
    ASSERT_TRUE(env.set()) << mode;
    for (int k = 0; k <= 15; ++k) {
      const int size = 1 << k;
      std::vector<float> xs;
      for (uint32_t exp = 0; exp < 256; ++exp)
        for (uint32_t sign = 0; sign < 2; ++sign) {
          for (uint32_t m : {0u, 1u, 0x400000u, 0x7FFFFFu, 0x7FFFFEu}) xs.push_back(std::bit_cast<float>(sign << 31 | exp << 23 | m));
          for (int r = 0; r < (mode == 0 ? 16 : 4); ++r) xs.push_back(std::bit_cast<float>(sign << 31 | exp << 23 | mant(rng)));
        }
      // Next to the limit |x| W 2^8 = 2^30, both signs, and next to texel centres and edges.
      const float lim = std::ldexp(1.0f, 22 - k);
      for (float b : {lim, -lim})
        for (int d = -8; d <= 8; ++d) {
          uint32_t bits = std::bit_cast<uint32_t>(b);
          bits = static_cast<uint32_t>(static_cast<int64_t>(bits) + d);
          xs.push_back(std::bit_cast<float>(bits));
        }
      for (int i = -40; i <= 40; ++i)
        for (float off : {0.0f, 0.5f}) {
          const float c = (static_cast<float>(i) + off) / static_cast<float>(size);
          xs.push_back(c), xs.push_back(std::nextafter(c, -1e30f)), xs.push_back(std::nextafter(c, 1e30f));
        }
      std::shuffle(xs.begin(), xs.end(), rng);
      while (xs.size() % 4 != 0) xs.push_back(0.25f);
      for (size_t i = 0; i < xs.size(); i += 4) {
        check4_pow2({xs[i], xs[i + 1], xs[i + 2], xs[i + 3]}, size, compared, declined);
        if (HasFatalFailure()) return;
      }
      // Single lanes (the other three 0.5): every one of them decides alone.
      for (float x : xs) {
        check4_pow2({x, 0.5f, 0.5f, 0.5f}, size, compared, declined);
        if (HasFatalFailure()) return;
      }
      if (mode == 0)
        for (uint64_t b = 0; b < (uint64_t{1} << 32); b += 4093) {
          const float x = std::bit_cast<float>(static_cast<uint32_t>(b));
          check4_pow2({x, -x, 0.5f, x * 0.5f}, size, compared, declined);
          if (HasFatalFailure()) return;
        }
    }
  }
  EXPECT_GT(compared, 10'000'000u);
  EXPECT_GT(declined, 10'000u);  // groups left to texel_coord4 were seen
}

// The wrap unit of the batch (repeat on any extent, clamp to edge, clamp to border) against
// wrap_taps<kW, 2> on taps around and far outside every extent.
template <WrapMode kW>
void check_wrap(int size, const std::vector<int32_t>& starts) {
  for (size_t i = 0; i + 4 <= starts.size(); i += 4) {
    __m128i t0, t1;
    dp::fast::wrap2x4<kW>(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&starts[i])), size, t0, t1);
    alignas(16) std::array<int32_t, 4> a{}, b{};
    _mm_store_si128(reinterpret_cast<__m128i*>(a.data()), t0);
    _mm_store_si128(reinterpret_cast<__m128i*>(b.data()), t1);
    for (size_t k = 0; k < 4; ++k) {
      int want[2];
      dp::fast::wrap_taps<kW, 2>(starts[i + k], size, want);
      ASSERT_EQ(a[k], want[0]) << wrap_mode_name(kW) << " size " << size << " i0 " << starts[i + k];
      ASSERT_EQ(b[k], want[1]) << wrap_mode_name(kW) << " size " << size << " i0 " << starts[i + k];
    }
  }
}

TEST(TexelCoord4, WrapEqualsWrapTaps) {
  std::mt19937 rng(42);
  for (int size : extents(rng)) {
    std::vector<int32_t> starts;
    for (int32_t i = -3 * size - 5; i <= 3 * size + 5 && starts.size() < 4000; ++i) starts.push_back(i);
    for (int32_t i : {-(1 << 30) - 1, -(1 << 30), -65536, -1, 0, 1 << 30, (1 << 30) - 1, size - 2, size - 1, size}) starts.push_back(i);
    std::uniform_int_distribution<int32_t> any(-(1 << 30) - 1, 1 << 30);
    while (starts.size() % 4 != 0 || starts.size() < 8000) starts.push_back(any(rng));
    ASSERT_TRUE(dp::fast::wrap2x4_takes<WrapMode::Repeat>(size));  // any extent (the remainder unit off powers of two)
    check_wrap<WrapMode::Repeat>(size, starts);
    check_wrap<WrapMode::ClampToEdge>(size, starts);
    check_wrap<WrapMode::ClampToBorder>(size, starts);
    ASSERT_FALSE(HasFatalFailure());
  }
  EXPECT_FALSE(dp::fast::wrap2x4_takes<WrapMode::MirroredRepeat>(16));
}

// The remainder unit of repeat off powers of two (repeat_remainder4) against wrap_index on every
// extent 1..2^15: taps around 0 and the extent, around multiples of the extent near +-2^31 (where
// the binary64 quotient is least exact), INT32_MIN and INT32_MAX, random ones; on a sample of the
// extents again under the three other IEEE rounding modes and with FTZ and DAZ set.
TEST(TexelCoord4, RepeatRemainderEqualsWrapIndex) {
  std::mt19937 rng(44);
  std::uniform_int_distribution<int32_t> any(std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max());
  size_t compared = 0;
  for (int mode = 0; mode < FpEnvironment::kCount; ++mode) {
    const FpEnvironment env(mode);
    ASSERT_TRUE(env.set()) << mode;
    for (int size = 1; size <= 32768; size += mode == 0 ? 1 : 97) {
      std::vector<int32_t> xs;
      for (int32_t k = -3; k <= 3; ++k) xs.push_back(k), xs.push_back(size + k), xs.push_back(-size + k);
      const int64_t top = (int64_t{std::numeric_limits<int32_t>::max()} / size) * size;  // multiples near +-2^31
      for (int64_t m : {top, -top, top - size, -top + size})
        for (int64_t k : {-1, 0, 1})
          if (m + k >= std::numeric_limits<int32_t>::min() && m + k <= std::numeric_limits<int32_t>::max())
            xs.push_back(static_cast<int32_t>(m + k));
      xs.push_back(std::numeric_limits<int32_t>::min()), xs.push_back(std::numeric_limits<int32_t>::max());
      while (xs.size() % 4 != 0 || xs.size() < 48) xs.push_back(any(rng));
      for (size_t i = 0; i < xs.size(); i += 4) {
        alignas(16) std::array<int32_t, 4> r{};
        _mm_store_si128(reinterpret_cast<__m128i*>(r.data()),
                        dp::fast::repeat_remainder4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&xs[i])), size));
        for (size_t k = 0; k < 4; ++k) {
          const int want = wrap_index(WrapMode::Repeat, xs[i + k], size);
          if (r[k] != want) FAIL() << "size " << size << " i " << xs[i + k] << " mode " << mode << ": " << r[k] << " != " << want;
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 1'500'000u);
}

// Row offsets y w for 0 <= y < 2^15, 0 < w <= 2^15.
TEST(TexelCoord4, RowOffsetEqualsProduct) {
  std::mt19937 rng(43);
  std::uniform_int_distribution<int32_t> y(0, 32767), w(1, 32768);
  for (int i = 0; i < 200'000; ++i) {
    const std::array<int32_t, 4> ys{y(rng), y(rng), i % 7 == 0 ? 32767 : y(rng), i % 5 == 0 ? 0 : y(rng)};
    const int32_t ww = i % 3 == 0 ? 32768 : w(rng);
    alignas(16) std::array<int32_t, 4> r{};
    _mm_store_si128(reinterpret_cast<__m128i*>(r.data()),
                    dp::fast::row_offset4(_mm_setr_epi32(ys[0], ys[1], ys[2], ys[3]), _mm_set1_epi32(ww)));
    for (size_t k = 0; k < 4; ++k) ASSERT_EQ(r[k], ys[k] * ww);
    const int log2w = i % 16;  // the shift on every power-of-two width
    _mm_store_si128(reinterpret_cast<__m128i*>(r.data()),
                    dp::fast::row_offset4_pow2(_mm_setr_epi32(ys[0], ys[1], ys[2], ys[3]), log2w));
    for (size_t k = 0; k < 4; ++k) ASSERT_EQ(r[k], ys[k] * (1 << log2w));
  }
}

}  // namespace
}  // namespace tfu
#endif
