// The floating-point environment guard of the equality tests that sweep rounding modes
// (test_texel_coord4.cpp, test_raster_quad_avx.cpp). x86 (SSE) only: it sets MXCSR.
#pragma once

#include <xmmintrin.h>

#include <cfenv>

namespace tfu::test {

// The floating-point environments the tests run under, one by one: the four IEEE rounding modes
// (round to nearest first), then round to nearest with MXCSR's flush-to-zero and
// denormals-are-zero set. The previous environment comes back when the guard leaves scope, also on
// a failed assertion's return.
class FpEnvironment {
 public:
  static constexpr int kCount = 5;
  explicit FpEnvironment(int mode) : csr_(_mm_getcsr()) {
    static constexpr int kRounding[] = {FE_TONEAREST, FE_DOWNWARD, FE_UPWARD, FE_TOWARDZERO};
    if (mode < 4)
      set_ = std::fesetround(kRounding[mode]) == 0;
    else
      _mm_setcsr(csr_ | 0x8040u);  // FTZ and DAZ
  }
  ~FpEnvironment() {
    std::fesetround(FE_TONEAREST);
    _mm_setcsr(csr_);
  }
  FpEnvironment(const FpEnvironment&) = delete;
  FpEnvironment& operator=(const FpEnvironment&) = delete;
  bool set() const { return set_; }

 private:
  unsigned csr_;
  bool set_ = true;
};

}  // namespace tfu::test
