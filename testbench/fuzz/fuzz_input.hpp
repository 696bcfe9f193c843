// Helpers of the fuzz targets (docs/fuzzing.md): a reader that turns the fuzzer's bytes into
// typed choices, and the entry point every target defines. Each target compiles two ways: as a
// libFuzzer target (clang, -DTFU_FUZZ=ON, scripts/fuzz) and, in every normal build, linked with
// replay_main.cpp into fuzz_replay_<name>, which ctest runs over the target's corpus
// (testbench/fuzz/corpus/<name>/), so a found input stays a regression case.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace tfu::fuzz {

// Consumes the input front to back; past the end every read returns zeros.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  size_t remaining() const { return size_ - pos_; }
  uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = v << 8 | byte();
    return v;
  }
  // An integer in [lo, hi] (hi - lo < 2^32).
  int64_t in_range(int64_t lo, int64_t hi) {
    const auto span = static_cast<uint64_t>(hi - lo) + 1;
    const uint64_t v = span <= 256 ? byte() : u32();
    return lo + static_cast<int64_t>(v % span);
  }
  bool flag() { return byte() & 1u; }
  // A float from 32 raw bits: every bit pattern, NaNs, infinities and denormals included.
  float raw_float() {
    const uint32_t b = u32();
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
  // Mostly ordinary coordinates (k/64 - 2 .. 2), sometimes any bit pattern.
  float coordinate() {
    const uint8_t kind = byte();
    if (kind < 200) return static_cast<float>(static_cast<int>(u32() % 257) - 128) / 64.0f + static_cast<float>(byte()) / 16384.0f;
    return raw_float();
  }
  template <typename T, size_t N>
  const T& pick(const T (&choices)[N]) {
    return choices[byte() % N];
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// The whole input as a string (JSON, trace text).
inline std::string as_text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

}  // namespace tfu::fuzz
