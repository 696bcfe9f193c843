#include "cmodel/q3_textures.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/pk3.hpp"

namespace tfu::q3 {

const char* surface_class_name(SurfaceClass c) { return kSurfaceClassNames.name(c); }

bool name_marks_invisible(const std::string& name) {
  const std::string lower = ascii_lower(name);
  const size_t slash = lower.rfind('/');
  const std::string leaf = slash == std::string::npos ? lower : lower.substr(slash + 1);
  for (const char* token : kInvisibleNameTokens)
    if (leaf.find(token) != std::string::npos) return true;
  return false;
}

SurfaceClass classify_surface(const BspTexture& t) {
  if ((t.surface_flags & (kSurfNodraw | kSurfSkip)) != 0 || name_marks_invisible(t.name)) return SurfaceClass::Invisible;
  if ((t.surface_flags & kSurfSky) != 0) return SurfaceClass::Sky;
  return SurfaceClass::Drawn;
}

namespace {

std::string first_line(std::string s) {
  if (const auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s.substr(0, 160);
}

Image to_rgba8(const std::vector<uint8_t>& raw, int width, int height, int channels) {
  Image img(width, height);
  const auto nch = static_cast<size_t>(channels);
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const uint8_t* p = &raw[i * nch];
    switch (channels) {
      case 1: img.texels[i] = {p[0], p[0], p[0], 255}; break;
      case 2: img.texels[i] = {p[0], p[0], p[0], p[1]}; break;
      case 3: img.texels[i] = {p[0], p[1], p[2], 255}; break;
      default: img.texels[i] = {p[0], p[1], p[2], p[3]}; break;
    }
  }
  return img;
}

}  // namespace

Texture decode_image(std::span<const uint8_t> bytes, const std::string& name) {
  // IOMemReader only reads; its constructor takes a non-const pointer.
  OIIO::Filesystem::IOMemReader memreader(const_cast<uint8_t*>(bytes.data()), bytes.size());
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  void* proxy = &memreader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  auto in = OIIO::ImageInput::open(name, &config);
  if (!in) throw InputError(fmt::format("{}: cannot decode image: {}", name, first_line(OIIO::geterror())));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.width > kMaxTextureSize || spec.height > kMaxTextureSize || spec.nchannels < 1)
    throw InputError(fmt::format("{}: image of {}x{}x{} outside 1..{} per side", name, spec.width, spec.height,
                                 spec.nchannels, kMaxTextureSize));
  const int use = std::min(spec.nchannels, 4);
  // charged before decoding: a small RLE TGA can hold 16384 x 16384 texels (cmodel/memory_budget.hpp)
  auto charge = std::make_shared<MemoryCharge>(mip_chain_bytes(spec.width, spec.height), name, "decoded texels");
  std::vector<uint8_t> raw(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * static_cast<size_t>(use));
  if (!in->read_image(0, 0, 0, use, OIIO::TypeDesc::UINT8, raw.data()))
    throw InputError(fmt::format("{}: cannot decode pixels: {}", name, first_line(in->geterror())));
  Texture tex;
  tex.format = TexelFormat::RGBA8;
  tex.levels.push_back(to_rgba8(raw, spec.width, spec.height, use));
  tex.memory = std::move(charge);
  in->close();
  return tex;
}

Texture make_fallback_texture() {
  Texture tex;
  tex.format = TexelFormat::RGBA8;
  Image img(kFallbackSize, kFallbackSize);
  for (int y = 0; y < kFallbackSize; ++y)
    for (int x = 0; x < kFallbackSize; ++x) {
      const uint8_t g = ((x / kFallbackCell + y / kFallbackCell) % 2 == 0) ? kFallbackLight : kFallbackDark;
      img.at(x, y) = {g, g, g, 255};
    }
  tex.levels.push_back(std::move(img));
  generate_mipmaps(tex, MipMethod::Box);
  return tex;
}

TextureCache::TextureCache(const GameArchives& archives)
    : archives_(archives), fallback_(std::make_shared<const Texture>(make_fallback_texture())) {}

namespace {

std::vector<std::string> candidate_names(const std::string& name) {
  const std::string lower = ascii_lower(name);
  std::string stem = name;
  std::vector<std::string> out;
  if (lower.ends_with(".tga") || lower.ends_with(".jpg")) {
    out.push_back(name);
    stem = name.substr(0, name.size() - 4);
  }
  for (const char* ext : {".tga", ".jpg"})
    if (out.empty() || ascii_lower(stem + ext) != lower) out.push_back(stem + ext);
  return out;
}

}  // namespace

const ResolvedTexture& TextureCache::get(const std::string& name) {
  const std::string key = ascii_lower(name);
  if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
  ResolvedTexture r;
  for (const std::string& candidate : candidate_names(name)) {
    const auto ref = archives_.locate(candidate);
    if (!ref) continue;
    r.source = archives_.describe(*ref);
    Texture tex = decode_image(archives_.read(*ref), r.source);
    generate_mipmaps(tex, MipMethod::Box);
    r.texture = std::make_shared<const Texture>(std::move(tex));
    ++decoded_;
    break;
  }
  if (!r.texture) {
    r.texture = fallback_;
    r.fallback = true;
  }
  return cache_.emplace(key, std::move(r)).first->second;
}

}  // namespace tfu::q3
