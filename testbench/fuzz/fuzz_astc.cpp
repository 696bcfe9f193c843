// Fuzz target (i), astc (docs/fuzzing.md): ASTC images through the decoder (cmodel/astc_decode.hpp)
// and libastcenc 4.2.0, which must agree texel for texel except for the one known difference
// (testbench/astc_reference.hpp: HDR-endpoint partitions in the linear profile). The first byte
// chooses the footprint (byte % 14) and the operation mode (bit 7: sRGB); the next two the image
// width and height in blocks (1..4 each) and what the last block column and row keep (1..block
// size texels: partial edge blocks); the rest is the blocks, zeros past the input's end (a zero
// block is a reserved block mode). Any difference aborts with the block and the texel.
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "cmodel/astc_decode.hpp"
#include "testbench/astc_reference.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tfu::fuzz::ByteReader in(data, size);
  const uint8_t choice = in.byte();
  const tfu::AstcFootprint f = tfu::kAstcFootprints[choice % tfu::kAstcFootprints.size()];
  const bool srgb = (choice & 0x80u) != 0;
  const uint8_t wb = in.byte(), hb = in.byte();
  const int bx = 1 + wb % 4, by = 1 + hb % 4;
  const int width = (bx - 1) * f.w + 1 + (wb / 4) % f.w, height = (by - 1) * f.h + 1 + (hb / 4) % f.h;
  std::vector<uint8_t> blocks(static_cast<size_t>(bx * by) * tfu::kAstcBlockBytes);
  for (uint8_t& b : blocks) b = in.byte();

  const tfu::Image mine = tfu::decode_astc_image(blocks.data(), blocks.size(), width, height, f.w, f.h, srgb);
  const std::vector<tfu::Rgba8> ref =
      tfu::test::astcenc_decode_image(blocks.data(), blocks.size(), width, height, f.w, f.h, srgb);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const tfu::Rgba8 m = mine.at(x, y), r = ref[static_cast<size_t>(y * width + x)];
      if (m == r) continue;
      const uint8_t* blk = &blocks[static_cast<size_t>((y / f.h) * bx + x / f.w) * tfu::kAstcBlockBytes];
      if (tfu::test::is_known_hdr_partition_difference(blk, f.w, f.h, srgb, r, m)) continue;
      std::fprintf(stderr, "astc %dx%d %s texel (%d, %d) of a %dx%d image: decoder %d,%d,%d,%d libastcenc %d,%d,%d,%d\n",
                   f.w, f.h, srgb ? "srgb" : "linear", x, y, width, height, m.r, m.g, m.b, m.a, r.r, r.g, r.b, r.a);
      std::abort();
    }
  return 0;
}
