// Compression at upload: which block format a driver gives a texture, and the compressed texture
// itself (docs/compressed.md, "Real frames as they ship"). The texture key `compress`
// (cmodel/bindings.hpp) and OpenArena levels (`--compress` with an oa: scene, cmodel/q3_scene.hpp)
// take one rule by name:
//   none     no compression (the default)
//   FORMAT   any unsigned block format name of kBlockFormats (bc1, bc3, bc7, etc2, astc4x4 ...
//            astc12x12): every texture the rule is applied to, in that format
//   s3tc     ioquake3's upload rule with r_ext_compressed_textures 1 on a GL driver with
//            GL_EXT_texture_compression_s3tc (renderergl1/tr_image.c, Upload32): a texture whose
//            every texel of the uploaded image has alpha 255 is stored as
//            GL_COMPRESSED_RGBA_S3TC_DXT1_EXT (bc1a); a texture with any other alpha stays
//            uncompressed (GL_RGBA; renderergl1 never chooses DXT3 or DXT5). The scan is over
//            level 0, the image Upload32 scans; every MIP level then gets the same format.
// Light maps are never compressed: ioquake3 creates them with IMGFLAG_NO_COMPRESSION
// (renderergl1/tr_bsp.c, R_LoadLightmaps) and Upload32 gives light maps GL_RGB whatever the flags;
// the level scene applies the rule to base textures only.
//
// Encoding is cmodel/block_encode.hpp (libsquish for BC1-BC5, libastcenc for ASTC, the own
// encoders elsewhere) of each stored level, as a driver compresses each glTexImage2D level; the
// texture is then texture_from_block_image of the blocks (its levels the decoded texels the golden
// model samples; the blocks what texture memory stores and the cycle model decodes).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "cmodel/block_formats.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

enum class UploadRule : uint8_t { None, Format, S3tc };

struct UploadCompression {
  UploadRule rule = UploadRule::None;
  BlockFormat format = BlockFormat::BC1;  // UploadRule::Format only
  std::string name() const;               // "none", "s3tc" or the format's name
  friend bool operator==(const UploadCompression&, const UploadCompression&) = default;
};

inline constexpr const char* kUploadRuleS3tc = "s3tc";
// The s3tc rule's format for opaque textures: GL_COMPRESSED_RGBA_S3TC_DXT1_EXT.
inline constexpr BlockFormat kS3tcOpaqueFormat = BlockFormat::BC1A;

// "none", "s3tc" or an unsigned block format name; InputError (one line, "did you mean") otherwise.
UploadCompression upload_compression_from_name(const std::string& name);

// The block format the rule gives `texture` (its level 0 scanned for alpha under s3tc), or nullopt
// when it stays uncompressed. A texture that is compressed already keeps its blocks (nullopt).
std::optional<BlockFormat> upload_block_format(const UploadCompression& c, const Texture& texture);

// `texture`'s levels encoded in `f` and held as blocks; layout, tile size and memory charge kept.
// InputError (naming `what`) when the format has no encoder.
Texture compress_texture(const Texture& texture, BlockFormat f, const std::string& what);

// upload_block_format, then compress_texture, remembered for the process (thread-safe): the spawn
// points, modes and traces of one run that ask for the same texture and format encode it once.
// Returns `texture` itself when the rule leaves it uncompressed.
std::shared_ptr<const Texture> upload_compressed(const std::shared_ptr<const Texture>& texture,
                                                 const UploadCompression& c, const std::string& what);

}  // namespace tfu
