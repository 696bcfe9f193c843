// Iteration counts of the randomized tests (random vectors, random keys), one rule for every
// suite. The Release suite runs each count in full. Under AddressSanitizer (cmake -DTFU_SANITIZE=ON:
// GCC defines __SANITIZE_ADDRESS__, clang has __has_feature(address_sanitizer)) these loops run
// 10-40 times slower and the sanitizer suite runs a tenth of each count: a sanitizer finds a bad access or undefined behaviour on the paths a loop
// takes, and a tenth of the vectors still takes every path (shapes, tie classes, value ranges are
// cycled per vector, not drawn once); the full counts add values, which the Release suite checks.
// docs/fuzzing.md, "Sanitizer run".
#pragma once

namespace tfu::test {

#if defined(__SANITIZE_ADDRESS__)
#define TFU_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TFU_SANITIZED 1
#endif
#endif

#ifdef TFU_SANITIZED
inline constexpr int kIterationDivisor = 10;
#else
inline constexpr int kIterationDivisor = 1;
#endif

// n iterations, or n / 10 (at least 1) in a sanitizer build.
constexpr int iterations(int n) { return n / kIterationDivisor > 0 ? n / kIterationDivisor : 1; }

}  // namespace tfu::test
