// libastcenc 4.2.0 (Debian libastcenc-dev) as the outside ASTC decoder of the tests and the fuzz
// target: one context per footprint and profile, an image decode to RGBA8, and the one known
// difference between libastcenc and the specification (docs/compressed-astc.md). Link with
// astcenc::astcenc (testbench/CMakeLists.txt).
#pragma once

#include <astcenc.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "cmodel/astc_decode.hpp"

namespace tfu::test {

inline void astcenc_check(astcenc_error e, const char* what) {
  if (e == ASTCENC_SUCCESS) return;
  std::fprintf(stderr, "libastcenc: %s: %s\n", what, astcenc_get_error_string(e));
  std::abort();
}

// One context per (footprint, profile), decompress-only or able to compress, kept for the process.
inline astcenc_context* astcenc_ctx(int bw, int bh, bool srgb, bool compress) {
  struct Free {
    void operator()(astcenc_context* c) const { astcenc_context_free(c); }
  };
  static std::map<std::tuple<int, int, bool, bool>, std::unique_ptr<astcenc_context, Free>> contexts;
  auto& slot = contexts[{bw, bh, srgb, compress}];
  if (!slot) {
    astcenc_config cfg{};
    astcenc_check(astcenc_config_init(srgb ? ASTCENC_PRF_LDR_SRGB : ASTCENC_PRF_LDR, static_cast<unsigned>(bw),
                                      static_cast<unsigned>(bh), 1, ASTCENC_PRE_FAST,
                                      compress ? 0 : ASTCENC_FLG_DECOMPRESS_ONLY, &cfg),
                  "astcenc_config_init");
    astcenc_context* ctx = nullptr;
    astcenc_check(astcenc_context_alloc(&cfg, 1, &ctx), "astcenc_context_alloc");
    slot.reset(ctx);
  }
  return slot.get();
}

inline constexpr astcenc_swizzle kAstcencIdentity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};

// libastcenc's ASTCENC_TYPE_U8 decode of a width x height image stored as `data` (blocks in raster
// order), row-major.
inline std::vector<Rgba8> astcenc_decode_image(const uint8_t* data, size_t size, int width, int height, int bw, int bh,
                                               bool srgb) {
  std::vector<Rgba8> out(static_cast<size_t>(width) * static_cast<size_t>(height));
  void* slice = out.data();
  astcenc_image img{static_cast<unsigned>(width), static_cast<unsigned>(height), 1, ASTCENC_TYPE_U8, &slice};
  astcenc_context* ctx = astcenc_ctx(bw, bh, srgb, false);
  astcenc_check(astcenc_decompress_image(ctx, data, size, &img, &kAstcencIdentity, 0), "astcenc_decompress_image");
  astcenc_check(astcenc_decompress_reset(ctx), "astcenc_decompress_reset");
  return out;
}

constexpr bool is_hdr_cem(int cem) { return cem == 2 || cem == 3 || cem == 7 || cem == 11 || cem == 14 || cem == 15; }

// The one disagreement found: texels of a partition with an HDR endpoint mode decode in
// libastcenc 4.2.0's linear LDR profile to (254, 0, 254, 254), not to the error colour (255, 0,
// 255, 255) the spec prescribes (KDFS "Illegal Encodings", last paragraph). Accepted only there: a
// legal, non-void-extent block with an HDR mode, linear, exactly that pair.
inline bool is_known_hdr_partition_difference(const uint8_t* block, int bw, int bh, bool srgb, Rgba8 ref, Rgba8 mine) {
  if (srgb || !(mine == kAstcErrorColor) || !(ref == Rgba8{254, 0, 254, 254})) return false;
  const AstcBlockConfig c = astc_block_config(block, bw, bh);
  if (c.illegal != AstcIllegal::None || c.void_extent) return false;
  for (int p = 0; p < c.partitions; ++p)
    if (is_hdr_cem(c.cem[static_cast<size_t>(p)])) return true;
  return false;
}

}  // namespace tfu::test
