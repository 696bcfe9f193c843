// Quake III texture names -> decoded textures (docs/real-frames.md, "Textures").
//
// Classification of a BSP texture (shader) entry, checked in this order:
//   Invisible  surface flag SURF_NODRAW (0x80) or SURF_SKIP (0x200), or a name whose last path
//              component contains one of kInvisibleNameTokens (caulk, clip, hint, nodraw, trigger,
//              skip, ...; case-insensitive). Their faces are skipped.
//   Sky        surface flag SURF_SKY (0x4): the game draws a sky box there, whose images are named
//              only by shader scripts (not in the installed archives). Their faces are skipped.
//   Drawn      everything else.
//
// Resolution of a drawn name (Quake III R_LoadImage order): a name ending in .tga or .jpg is first
// looked up as given; then the stem + ".tga", then the stem + ".jpg"; each candidate in every
// archive (the last archive first, GameArchives). No match: the name is a shader-only name
// (defined by a shader script, e.g. "flareShader", "textures/liquids/tele") and gets the fallback
// texture.
//
// Decoding: OpenImageIO reads the entry from memory (IOMemReader proxy, the entry name's extension
// selects the reader); the result is always RGBA8 (grey -> (L, L, L, 255), RGB -> A = 255, alpha
// unassociated: the stored values), row 0 = top of the image (t grows downwards, as in Quake III,
// so texture coordinates need no flip). Sizes are kept as stored (Quake III would resample
// non-power-of-two images); a box MIP chain (Lee & Jen Eq. 8, mipmap.hpp) completes every texture.
// A corrupt image is an InputError naming the archive and entry.
//
// Fallback texture: 64 x 64 RGBA8, 8 x 8-texel checker squares of grey 160 and 96 (opaque), with a
// box MIP chain: neutral, visibly "not a game texture", and a real texture workload.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>

#include "cmodel/bsp.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/texture.hpp"

namespace tfu::q3 {

inline constexpr std::array<const char*, 12> kInvisibleNameTokens = {
    "caulk",       "clip",          "hint",       "nodraw",    "trigger", "skip",
    "areaportal",  "clusterportal", "antiportal", "donotenter", "nodrop", "lightgrid"};
inline constexpr int kFallbackSize = 64, kFallbackCell = 8;
inline constexpr uint8_t kFallbackLight = 160, kFallbackDark = 96;

enum class SurfaceClass { Drawn, Invisible, Sky };
inline constexpr EnumNames<SurfaceClass, 3> kSurfaceClassNames{
    "surface class",
    {{{SurfaceClass::Drawn, "drawn"}, {SurfaceClass::Invisible, "invisible"}, {SurfaceClass::Sky, "sky"}}}};
const char* surface_class_name(SurfaceClass c);  // kSurfaceClassNames

bool name_marks_invisible(const std::string& name);
SurfaceClass classify_surface(const BspTexture& t);

// Decodes one image file held in memory; `name` selects the reader by its extension and names the
// image in errors. One level, RGBA8 (see above).
Texture decode_image(std::span<const uint8_t> bytes, const std::string& name);
Texture make_fallback_texture();  // with its box MIP chain

struct ResolvedTexture {
  std::shared_ptr<const Texture> texture;  // box MIP chain; the shared fallback if `fallback`
  bool fallback = false;
  std::string source;  // "pak4-textures.pk3:textures/e7/e7walldesign01.jpg", empty for the fallback
};

// Resolves and decodes texture names of one game directory, keeping every result (also misses)
// for the lifetime of the cache: the levels and spawn points of one run decode each image once.
class TextureCache {
 public:
  explicit TextureCache(const GameArchives& archives);
  const ResolvedTexture& get(const std::string& name);
  const std::shared_ptr<const Texture>& fallback() const { return fallback_; }
  size_t decoded() const { return decoded_; }  // images decoded so far

 private:
  const GameArchives& archives_;
  std::shared_ptr<const Texture> fallback_;
  std::map<std::string, ResolvedTexture> cache_;  // key: lower-case name
  size_t decoded_ = 0;
};

}  // namespace tfu::q3
