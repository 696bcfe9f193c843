#include "cmodel/texture.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "cmodel/block_formats.hpp"
#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/stderr_capture.hpp"
#include "cmodel/texture_containers.hpp"

namespace tfu {

Image::Image(int w, int h, Rgba8 fill)
    : width(w), height(h), texels(static_cast<size_t>(w) * static_cast<size_t>(h), fill) {}

int mip_level_count(int width, int height) {
  int n = 1;
  for (int m = std::max(width, height); m > 1; m >>= 1) ++n;
  return n;
}

TexelFormat texel_format_from_name(const std::string& name) { return kTexelFormatNames.from_name(name); }
const char* texel_format_name(TexelFormat f) { return kTexelFormatNames.name(f); }

MemoryLayout memory_layout_from_name(const std::string& name) { return kMemoryLayoutNames.from_name(name); }
const char* memory_layout_name(MemoryLayout l) { return kMemoryLayoutNames.name(l); }

void Texture::validate(const std::string& what) const {
  if (levels.empty()) throw InputError(fmt::format("{}: texture has no levels", what));
  if (!valid_tile_bytes(tile_bytes))
    throw InputError(fmt::format("{}: tile of {} bytes (expected 64, 256 or 1024)", what, tile_bytes));
  const int w = width(), h = height();
  if (w < 1 || h < 1 || w > kMaxTextureSize || h > kMaxTextureSize)
    throw InputError(fmt::format("{}: size {}x{} outside 1..{} per side", what, w, h, kMaxTextureSize));
  if (static_cast<int>(levels.size()) > mip_level_count(w, h))
    throw InputError(fmt::format("{}: {} levels, a {}x{} chain has at most {}", what, levels.size(), w, h,
                                 mip_level_count(w, h)));
  for (int l = 0; l < static_cast<int>(levels.size()); ++l) {
    const Image& im = levels[static_cast<size_t>(l)];
    if (im.width != mip_extent(w, l) || im.height != mip_extent(h, l) ||
        im.texels.size() != static_cast<size_t>(im.width) * static_cast<size_t>(im.height))
      throw InputError(fmt::format("{}: level {} is {}x{}, the floor rule needs {}x{}", what, l, im.width,
                                   im.height, mip_extent(w, l), mip_extent(h, l)));
  }
}

WrapMode wrap_mode_from_name(const std::string& name) { return kWrapModeNames.from_name(name); }
const char* wrap_mode_name(WrapMode m) { return kWrapModeNames.name(m); }
const std::vector<std::string>& wrap_mode_names() {
  static const std::vector<std::string> names = kWrapModeNames.names();
  return names;
}

namespace {

// OpenImageIO's (possibly multi-line) error text for our one line, which names the file already:
// the first line, with the file's path (OIIO repeats it in full, however long) as "the file",
// control characters as '?', cut to kMaxLibraryTextChars.
inline constexpr size_t kMaxLibraryTextChars = 120;
std::string library_text(std::string s, const std::string& path) {
  const auto nl = s.find('\n');
  if (nl != std::string::npos) s.resize(nl);
  for (size_t at = path.empty() ? std::string::npos : s.find(path); at != std::string::npos; at = s.find(path, at + 8))
    s.replace(at, path.size(), "the file");
  return s.empty() ? std::string("unknown error") : quote_input(s, kMaxLibraryTextChars);
}

// `path` the file, `name` it quoted for messages.
// `charge`, when given: the memory budget's charge for the whole MIP chain of this level's size, made
// before the pixels are read (cmodel/memory_budget.hpp).
Image read_level(OIIO::ImageInput& in, int subimage, int miplevel, const std::string& path, const std::string& name,
                 bool* is_gray, std::shared_ptr<MemoryCharge>* charge = nullptr) {
  if (!in.seek_subimage(subimage, miplevel))
    throw InputError(fmt::format("{}: cannot read MIP level {}: {}", name, miplevel, library_text(in.geterror(), path)));
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width < 1 || spec.height < 1 || spec.width > kMaxTextureSize || spec.height > kMaxTextureSize)
    throw InputError(fmt::format("{}: image size {}x{} outside 1..{} per side", name, spec.width, spec.height,
                                 kMaxTextureSize));
  const int nch = spec.nchannels;
  if (nch < 1) throw InputError(fmt::format("{}: image has no channels", name));
  const int use = std::min(nch, 4);
  if (charge) *charge = std::make_shared<MemoryCharge>(mip_chain_bytes(spec.width, spec.height), name, "decoded texels");
  std::vector<uint8_t> raw(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) *
                           static_cast<size_t>(use));
  if (!in.read_image(subimage, miplevel, 0, use, OIIO::TypeDesc::UINT8, raw.data()))
    throw InputError(fmt::format("{}: cannot decode pixels: {}", name, library_text(in.geterror(), path)));
  Image img(spec.width, spec.height);
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const uint8_t* p = &raw[i * static_cast<size_t>(use)];
    Rgba8& t = img.texels[i];
    switch (use) {
      case 1: t = {p[0], p[0], p[0], 255}; break;
      case 2: t = {p[0], p[0], p[0], p[1]}; break;
      case 3: t = {p[0], p[1], p[2], 255}; break;
      default: t = {p[0], p[1], p[2], p[3]}; break;
    }
  }
  if (is_gray) *is_gray = (use == 1);
  return img;
}

std::unique_ptr<OIIO::ImageInput> open_input(const std::string& path) {
  check_input_file(path, quote_path(path), kMaxImageBytes);  // a regular file of bounded size (never a FIFO)
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // filter the stored values, as GL does
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) throw InputError(fmt::format("{}: cannot open image: {}", quote_path(path), library_text(OIIO::geterror(), path)));
  return in;
}

Texture load_texture_file(const std::string& path) {
  auto in = open_input(path);
  Texture tex;
  bool gray = false;
  const std::string name = quote_path(path);  // for messages
  tex.levels.push_back(read_level(*in, 0, 0, path, name, &gray, &tex.memory));
  tex.format = gray ? TexelFormat::L8 : TexelFormat::RGBA8;
  const int w = tex.levels[0].width, h = tex.levels[0].height;
  for (int l = 1; l < mip_level_count(w, h); ++l) {
    if (!in->seek_subimage(0, l)) break;  // the file holds no more levels
    tex.levels.push_back(read_level(*in, 0, l, path, name, nullptr));
  }
  in->close();
  tex.validate(name);
  return tex;
}

// Runs an OpenImageIO call with stderr captured; an InputError carries what libraries printed.
template <typename F>
auto with_stderr_captured(F&& f) {
  StderrCapture capture;
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(with_captured(e.what(), capture));
  }
}

}  // namespace

namespace {
// A directory `tfu mipmap --out` wrote: level_00.png, level_01.png, ... read in order while they
// exist; the chain is checked by Texture::validate (sizes by the floor rule).
Texture load_level_directory(const std::string& dir) {
  const auto level_path = [&dir](int l) { return (std::filesystem::path(dir) / fmt::format("level_{:02d}.png", l)).string(); };
  if (!std::filesystem::is_regular_file(level_path(0)))
    throw InputError(fmt::format("{}: a directory without level_00.png (tfu mipmap --out writes level_NN.png)", quote_path(dir)));
  Texture tex;
  bool gray = false;
  const int max_levels = mip_level_count(kMaxTextureSize, kMaxTextureSize);
  for (int l = 0; l < max_levels && std::filesystem::is_regular_file(level_path(l)); ++l) {
    auto in = open_input(level_path(l));
    tex.levels.push_back(read_level(*in, 0, 0, level_path(l), quote_path(level_path(l)), l == 0 ? &gray : nullptr,
                                    l == 0 ? &tex.memory : nullptr));
    in->close();
  }
  tex.format = gray ? TexelFormat::L8 : TexelFormat::RGBA8;
  tex.validate(quote_path(dir));
  return tex;
}
}  // namespace

Texture load_texture(const std::string& path) {
  std::error_code ec;  // an unusable name is the file reader's error (one line naming it)
  if (std::filesystem::is_directory(path, ec)) return with_stderr_captured([&] { return load_level_directory(path); });
  if (is_block_container_file(path)) {  // DDS, KTX or .astc: blocks, decoded as the unit decodes them
    const BlockImage image = read_block_image(path, quote_path(path));
    return texture_from_block_image(image, BlockDecodeRules{{}, image.srgb}, quote_path(path));
  }
  return with_stderr_captured([&] { return load_texture_file(path); });
}

Image load_image(const std::string& path) {
  return with_stderr_captured([&] {
    auto in = open_input(path);
    Image img = read_level(*in, 0, 0, path, quote_path(path), nullptr);
    in->close();
    return img;
  });
}

void write_image_file(const Image& img, const std::string& type_path, const std::string& file_path) {
  with_stderr_captured([&] {
    auto out = OIIO::ImageOutput::create(type_path);
    if (!out)
      throw InputError(fmt::format("{}: no image writer for this file type: {}", quote_path(type_path), library_text(OIIO::geterror(), file_path)));
    OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out->open(file_path, spec))
      throw InputError(fmt::format("{}: cannot write: {}", quote_path(type_path), library_text(out->geterror(), file_path)));
    if (!out->write_image(OIIO::TypeDesc::UINT8, img.texels.data()))
      throw InputError(fmt::format("{}: cannot write: {}", quote_path(type_path), library_text(out->geterror(), file_path)));
    if (!out->close()) throw InputError(fmt::format("{}: cannot write: {}", quote_path(type_path), library_text(out->geterror(), file_path)));
    return 0;
  });
}

bool image_writer_exists(const std::string& type_path) {
  return with_stderr_captured([&] { return OIIO::ImageOutput::create(type_path) != nullptr; });
}

void save_image(const Image& img, const std::string& path, bool overwrite) {
  std::error_code ec;
  if (!overwrite && std::filesystem::exists(path, ec))
    throw InputError(fmt::format("{}: exists (pass --force to overwrite)", path));
  write_image_file(img, path, path);
}

}  // namespace tfu
