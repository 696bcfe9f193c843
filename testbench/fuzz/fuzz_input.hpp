// Helpers of the fuzz targets (docs/fuzzing.md): a reader that turns the fuzzer's bytes into
// typed choices, and the entry point every target defines. Each target compiles two ways: as a
// libFuzzer target (clang, -DTFU_FUZZ=ON, scripts/fuzz) and, in every normal build, linked with
// replay_main.cpp into fuzz_replay_<name>, which ctest runs over the target's corpus
// (testbench/fuzz/corpus/<name>/), so a found input stays a regression case.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

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
  // A name as files, archives and users spell them, hostile ones included (docs/fuzzing.md): past
  // the input's end the ordinary "fuzz"; else one of
  //   raw bytes of the input (0..64: control characters, NUL, bytes that are not UTF-8),
  //   very long (256..4,096 bytes, with separators), path-like (`..` runs, an absolute path,
  //   backslashes, a trailing separator), words of the line formats (spaces, '%', '=', '#', '|',
  //   ',', quotes, braces), UTF-8 text, or an ordinary name with one control character in it.
  std::string name() {
    switch (byte() % 8) {
      case 0:
        return "fuzz";
      case 1: {
        std::string s;
        for (size_t n = byte() % 65; n > 0; --n) s += static_cast<char>(byte());
        return s;
      }
      case 2: {
        std::string s(static_cast<size_t>(in_range(256, 4096)), 'n');
        for (size_t k = byte() % 16; k < s.size(); k += 1 + byte() % 200) s[k] = byte() & 1 ? '/' : ' ';
        return s;
      }
      case 3: {
        static const char* const kPaths[] = {"../../../../etc/passwd", "/etc/hostname", "..", "./a/../../b",
                                             "a\\..\\b.png", "dir/", "//double//slash", "-rf"};
        return pick(kPaths);
      }
      case 4: {
        static const char* const kWords[] = {"a b.png", "c.png mipmaps=none", "100% real", "k=v",
                                             "# tfu-texture 1 /etc/hostname", "a|b,c", "\"quoted\" 'single'",
                                             "{} %s %n $(x) `y`"};
        return pick(kWords);
      }
      case 5: {
        static const char* const kText[] = {"caf\xc3\xa9", "\xe6\xbc\xa2\xe5\xad\x97", "\xf0\x9f\x98\x80", "\xef\xbb\xbf\142om"};  // \142: 'b' (a hex escape would take it)
        return pick(kText);
      }
      default: {
        std::string s = "tex_name.png";
        const uint8_t c = byte();
        s.insert(s.begin() + static_cast<std::ptrdiff_t>(byte() % (s.size() + 1)), static_cast<char>(c % 2 ? 0x7f : c % 32));
        return s;
      }
    }
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

// The whole input as a string (JSON, trace text).
inline std::string as_text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// An image of 4x4-texel blocks read from the input: two bytes give the blocks per side (1..4) and
// how many texels the last block column and row keep (partial edge blocks); then the blocks, row by
// row, zeros past the input's end.
struct FuzzBlockImage {
  int blocks_x = 1, blocks_y = 1, width = 1, height = 1;
  size_t block_bytes = 0;
  std::vector<uint8_t> blocks;
  // The block holding texel (x, y).
  std::span<const uint8_t> block_at(int x, int y) const {
    return std::span<const uint8_t>(blocks).subspan(static_cast<size_t>((y / 4) * blocks_x + x / 4) * block_bytes,
                                                    block_bytes);
  }
};
inline FuzzBlockImage read_block_image(ByteReader& in, size_t block_bytes) {
  FuzzBlockImage img;
  const uint8_t wb = in.byte(), hb = in.byte();
  img.blocks_x = 1 + wb % 4;
  img.blocks_y = 1 + hb % 4;
  img.width = (img.blocks_x - 1) * 4 + 1 + (wb / 4) % 4;
  img.height = (img.blocks_y - 1) * 4 + 1 + (hb / 4) % 4;
  img.block_bytes = block_bytes;
  img.blocks.resize(static_cast<size_t>(img.blocks_x * img.blocks_y) * block_bytes);
  for (uint8_t& b : img.blocks) b = in.byte();
  return img;
}

}  // namespace tfu::fuzz
