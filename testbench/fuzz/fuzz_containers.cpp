// Fuzz target: the block-compressed file readers (cmodel/texture_containers.hpp; docs/fuzzing.md).
// The first byte chooses the reader (byte % 3: DDS, KTX 1.1, .astc), whose magic number is put in
// front of the rest of the input, so the fuzzer spends its time in the headers, not in finding the
// magic; parse_block_image then reads the bytes as `tfu decompress` and every texture input do.
// A file that reads must be well formed (validate_block_image), and written back to the same
// container (serialize_block_image) read again to the same image (format, sRGB flag, every level's
// size and blocks); its smallest level is decoded (decode_block_level, any format). A refused file must end in an
// InputError whose message is one line naming the input, at most kMaxMessageChars.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cmodel/error.hpp"
#include "cmodel/texture_containers.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

const std::vector<uint8_t> kMagic[3] = {
    {'D', 'D', 'S', ' '}, {0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'}, {0x13, 0xAB, 0xA1, 0x5C}};

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > (1 << 20)) return 0;
  std::vector<uint8_t> file = kMagic[data[0] % 3];
  file.insert(file.end(), data + 1, data + size);
  const std::string label = "'fuzz.bin'";
  try {
    const tfu::BlockImage img = tfu::parse_block_image(file, label);
    tfu::validate_block_image(img, "fuzz");
    const tfu::BlockContainer c = *tfu::container_by_magic(file);
    const std::vector<uint8_t> again = tfu::serialize_block_image(img, c, "fuzz");
    const tfu::BlockImage back = tfu::parse_block_image(again, "fuzz");
    if (back.format != img.format || back.srgb != img.srgb || back.levels.size() != img.levels.size())
      fail("written back, the file reads differently", tfu::block_format_name(img.format));
    for (size_t l = 0; l < img.levels.size(); ++l)
      if (back.levels[l].blocks != img.levels[l].blocks || back.levels[l].width != img.levels[l].width)
        fail("written back, a level reads differently", std::to_string(l));
    const tfu::BlockLevel& last = img.levels.back();
    if (static_cast<int64_t>(last.width) * last.height <= 256 * 256)
      (void)tfu::decode_block_level(img.format, last.width, last.height, last.blocks, {.srgb = img.srgb}, "fuzz");
  } catch (const tfu::InputError& e) {
    const std::string message = e.what();
    if (message.size() > tfu::kMaxMessageChars || tfu::has_control_characters(message) ||
        message.rfind(label + ": ", 0) != 0)
      fail("the error line is not one short line naming the input", message);
  }
  return 0;
}
