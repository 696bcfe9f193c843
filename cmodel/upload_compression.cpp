#include "cmodel/upload_compression.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <utility>

#include <fmt/format.h>

#include "cmodel/block_encode.hpp"
#include "cmodel/error.hpp"

namespace tfu {
namespace {

// The encoders' effort at upload (BlockEncodeOptions::quality): a driver compresses at upload with a
// fast encoder, so libsquish's range fit and libastcenc's fast preset (ASTCENC_PRE_FAST, 10) stand
// in for it (docs/compressed.md, "Real frames as they ship").
constexpr int kUploadEncodeQuality = 10;

}  // namespace

std::string UploadCompression::name() const {
  switch (rule) {
    case UploadRule::None: return "none";
    case UploadRule::S3tc: return kUploadRuleS3tc;
    case UploadRule::Format: return block_format_name(format);
  }
  return "none";
}

UploadCompression upload_compression_from_name(const std::string& name) {
  if (name == "none") return {};
  if (name == kUploadRuleS3tc) return {UploadRule::S3tc, kS3tcOpaqueFormat};
  const BlockFormat f = block_format_from_name(name);  // its one-line error lists the formats
  if (!unit_filterable(f))
    throw InputError(fmt::format("'{}' is a signed format; the unit filters unsigned texels only", name));
  return {UploadRule::Format, f};
}

std::optional<BlockFormat> upload_block_format(const UploadCompression& c, const Texture& texture) {
  if (texture.compressed || texture.levels.empty()) return std::nullopt;
  switch (c.rule) {
    case UploadRule::None: return std::nullopt;
    case UploadRule::Format: return c.format;
    case UploadRule::S3tc: {
      // Upload32: samples = 4 as soon as one texel's alpha is not 255; only samples == 3 compresses.
      const std::vector<Rgba8>& t = texture.levels.front().texels;
      const bool opaque = std::all_of(t.begin(), t.end(), [](const Rgba8& p) { return p.a == 255; });
      return opaque ? std::optional<BlockFormat>(kS3tcOpaqueFormat) : std::nullopt;
    }
  }
  return std::nullopt;
}

Texture compress_texture(const Texture& texture, BlockFormat f, const std::string& what) {
  // An srgba8 texture is encoded with the sRGB error metric and decoded by the sRGB rules (docs/srgb.md).
  const bool srgb = texture.format == TexelFormat::SRGBA8;
  const BlockImage blocks = encode_block_image(texture.levels, f, srgb, BlockEncodeOptions{kUploadEncodeQuality});
  Texture out = texture_from_block_image(blocks, BlockDecodeRules{{}, srgb}, what, texture.layout, texture.tile_bytes);
  out.memory = texture.memory;  // the budget's charge for the decoded chain stays with the texture
  if (srgb) out.format = TexelFormat::SRGBA8;
  return out;
}

std::shared_ptr<const Texture> upload_compressed(const std::shared_ptr<const Texture>& texture,
                                                 const UploadCompression& c, const std::string& what) {
  if (!texture) return texture;
  const std::optional<BlockFormat> f = upload_block_format(c, *texture);
  if (!f) return texture;
  // Keyed by the source texture (kept alive by the entry) and the format. Encoding runs outside the
  // lock; two threads that race on one key encode twice and keep the first result.
  using Key = std::pair<const Texture*, BlockFormat>;
  static std::mutex mutex;
  static std::map<Key, std::pair<std::shared_ptr<const Texture>, std::shared_ptr<const Texture>>> cache;
  const Key key{texture.get(), *f};
  {
    const std::lock_guard lock(mutex);
    if (const auto it = cache.find(key); it != cache.end()) return it->second.second;
  }
  auto compressed = std::make_shared<const Texture>(compress_texture(*texture, *f, what));
  const std::lock_guard lock(mutex);
  return cache.try_emplace(key, texture, std::move(compressed)).first->second.second;
}

}  // namespace tfu
