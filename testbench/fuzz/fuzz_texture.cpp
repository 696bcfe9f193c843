// Fuzz target (d): texture decoding through OpenImageIO (docs/fuzzing.md). The first byte chooses
// the file type (PNG, JPEG, TGA: byte % 3) and the file's name (byte / 3: "input" or a hostile
// name, see kNames), the rest is the file. It is written to a private temporary directory
// (TempDir) and loaded with load_texture, exactly as `--texture FILE` does; a texture that loads
// must satisfy Texture::validate and get a MIP chain. Bad files must end in an InputError whose
// message is one line that quotes the name within the length of an error line (no control
// character, at most kMaxMessageChars).
//
// Cost limit of the harness: images whose header claims more than 512 x 512 texels are skipped
// (the loader itself accepts up to 16384 x 16384, which is 1 GiB of texels per level).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/stderr_capture.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/texture.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& work_dir() {
  static const tfu::TempDir d("tfu-fuzz-texture", fs::exists("/dev/shm") ? "/dev/shm" : "");
  return d.path();
}

// File names as users and archives spell them (a file name holds any byte but '/' and NUL).
const char* const kNames[] = {"input", "a b", "c.png mipmaps=none", "new\nline", "tab\tcr\r", "caf\xc3\xa9", "\xff\xfe",
                              "-rf", "..x", "%s%n", "\x7f"};

std::string file_name(uint8_t choice) {
  const size_t k = choice / 3;
  if (k < std::size(kNames)) return kNames[k];
  return std::string(150 + k, 'n');  // long, within the file system's 255-byte limit
}

// The header's size, through the same reader (stderr captured: libpng may print).
bool small_enough(const std::string& path) {
  tfu::StderrCapture quiet;
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    (void)OIIO::geterror();
    return true;  // load_texture reports the error
  }
  const OIIO::ImageSpec& s = in->spec();
  const bool ok = static_cast<int64_t>(s.width) * s.height <= 512 * 512 && s.nchannels <= 64 && s.depth <= 1;
  in->close();
  return ok;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 262144) return 0;
  static const char* const kExt[] = {"png", "jpg", "tga"};
  const fs::path path = work_dir() / fmt::format("{}.{}", file_name(data[0]), kExt[data[0] % 3]);
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  if (small_enough(path.string())) {
    try {
      tfu::Texture t = tfu::load_texture(path.string());
      t.validate("fuzz");  // load_texture validates; a texture that loads must stay valid
      if (t.levels.size() == 1) tfu::generate_mipmaps(t, tfu::MipMethod::Box);
      t.validate("fuzz mips");
      tfu::load_image(path.string());
    } catch (const tfu::InputError& e) {
      const std::string message = e.what();
      if (message.size() > tfu::kMaxMessageChars || tfu::has_control_characters(message)) {
        std::fprintf(stderr, "the error line is not one short line (%zu characters): %s\n", message.size(), message.c_str());
        std::abort();
      }
    }
  }
  fs::remove(path);
  return 0;
}
