// tfu compress: encode a texture (file or procedural, with its MIP levels) into a block-compressed
// file (DDS, KTX 1.1 or .astc: cmodel/texture_containers.hpp); tfu decompress: decode one level of
// such a file to an image (docs/compressed-files.md).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cmodel/bindings.hpp"
#include "cmodel/block_encode.hpp"
#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/texture_containers.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct CompressOptions {
  std::string format;
  bool srgb = false;
  std::string texture;
  std::string mipmaps;  // empty: "auto" (box levels unless the file has its own), "none" for .astc
  int quality = 60;
  std::string out;
  bool force = false;
};

// The container of OUT's extension (.dds, .ktx, .astc, any case), else the format's default.
BlockContainer container_for(const std::string& out, BlockFormat f) {
  std::string ext = std::filesystem::path(out).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".dds") return BlockContainer::DDS;
  if (ext == ".ktx") return BlockContainer::KTX;
  if (ext == ".astc") return BlockContainer::ASTC;
  return default_container(f);
}

void run_compress(const CompressOptions& o) {
  const BlockFormat format = block_format_from_name(o.format);
  const BlockFormatInfo& info = block_format_info(format);
  if (o.srgb && info.gl_srgb_internal_format == 0)
    throw InputError(fmt::format("--srgb: {} has no sRGB variant", info.name));
  if (o.quality < 0 || o.quality > 100) throw InputError(fmt::format("--quality {} is outside 0..100", o.quality));
  const BlockContainer container = container_for(o.out, format);
  const std::string out_label = fmt::format("--out {}", quoted_path(o.out));
  if (!container_holds(container, format))
    throw InputError(fmt::format(
        "{}: {} cannot hold {} ({} holds the {} formats)", out_label, container_file_text(container), info.name,
        container == BlockContainer::DDS ? "DDS" : ".astc", container == BlockContainer::DDS ? "BC" : "ASTC"));
  std::string mipmaps = o.mipmaps.empty() ? (container == BlockContainer::ASTC ? "none" : "auto") : o.mipmaps;
  if (container == BlockContainer::ASTC && mipmaps != "none")
    throw InputError(
        fmt::format("--mipmaps '{}': an .astc file holds one level (use --mipmaps none, or a .ktx file for MIP levels)",
                    quote_input(mipmaps)));
  if (container == BlockContainer::ASTC && o.srgb)
    throw InputError("--srgb: an .astc file has no sRGB flag (use a .ktx file)");
  OutputFiles outputs(o.force);
  OutputFile& file = outputs.add("--out", o.out);
  const Texture tex = *load_texture_spec({o.texture, {{"mipmaps", mipmaps}}}, "--texture").texture;
  const BlockImage img = encode_block_image(tex.levels, format, o.srgb, BlockEncodeOptions{o.quality});
  const std::vector<uint8_t> bytes = serialize_block_image(img, container, out_label);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  outputs.commit();
  // Per level: size, bytes, and the PSNR (RGB, dB) of the decoded level against the source level
  // for the colour formats.
  std::cout << "level   width x height     bytes  psnr_db\n";
  for (size_t l = 0; l < img.levels.size(); ++l) {
    const BlockLevel& level = img.levels[l];
    std::string psnr = "-";
    if (info.channels >= 3) {
      const double p =
          psnr_db(decode_block_level(format, level.width, level.height, level.blocks, {.srgb = o.srgb}), tex.levels[l]);
      psnr = std::isinf(p) ? "inf" : fmt::format("{:.2f}", p);
    }
    std::cout << fmt::format("{:5d}   {:5d} x {:<5d} {:>10d}  {}\n", l, level.width, level.height, level.blocks.size(),
                             psnr);
  }
  print_summary_line(fmt::format("tfu compress: wrote {} ({}{} in {}, {} levels, {} bytes; encoder {})", o.out,
                                 info.name, o.srgb ? " sRGB" : "", block_container_name(container), img.levels.size(),
                                 bytes.size(), block_encoder_name(format)));
}

struct DecompressOptions {
  std::string in;
  std::string out;
  int level = 0;
  bool force = false;
};

void run_decompress(const DecompressOptions& o) {
  OutputFiles outputs(o.force);
  OutputFile& file = outputs.add_image("--out", o.out);
  const std::string label = quoted_path(o.in);
  const BlockImage img = read_block_image(o.in, label);
  if (o.level < 0 || o.level >= static_cast<int>(img.levels.size()))
    throw InputError(fmt::format("--level {}: {} has {} level{} (0..{})", o.level, label, img.levels.size(),
                                 img.levels.size() == 1 ? "" : "s", img.levels.size() - 1));
  const BlockLevel& level = img.levels[static_cast<size_t>(o.level)];
  const BlockFormatInfo& info = block_format_info(img.format);
  MemoryCharge charge(uint64_t{4} * static_cast<uint64_t>(level.width) * static_cast<uint64_t>(level.height), label,
                      "decoded texels");
  Image decoded = decode_block_level(img.format, level.width, level.height, level.blocks, {.srgb = img.srgb}, label);
  if (info.is_signed)  // SNORM8 (two's complement) stored as value + 128: -127..127 -> 1..255, 0 -> 128
    for (Rgba8& t : decoded.texels)
      t = Rgba8{snorm8_to_image_byte(static_cast<int8_t>(t.r)),
                info.channels == 2 ? snorm8_to_image_byte(static_cast<int8_t>(t.g)) : uint8_t{0}, 0, 255};
  file.write_image(decoded);
  outputs.commit();
  std::cout << fmt::format("level {}  {} x {}  {}{}  {}\n", o.level, level.width, level.height, info.name,
                           img.srgb ? " sRGB" : "", o.out);
}

}  // namespace

void register_compress(CLI::App& app) {
  auto c = std::make_shared<CompressOptions>();
  CLI::App* cmd = app.add_subcommand("compress", "Encode a texture and its MIP levels into a DDS, KTX or .astc file");
  cmd->add_option("--format", c->format,
                  "bc1 bc1a bc2 bc3 bc4 bc4s bc5 bc5s bc7 etc2 etc2a1 etc2a eac_r11 eac_r11s eac_rg11 eac_rg11s "
                  "astc4x4 .. astc12x12 (signed formats read the image's bytes v as v - 128)")
      ->required();
  cmd->add_flag("--srgb", c->srgb, "Mark the texture sRGB (ASTC: encoded with libastcenc's sRGB profile)");
  cmd->add_option("--texture", c->texture, "Base level: image file or proc:NAME[:SIZE]")->required();
  cmd->add_option("--mipmaps", c->mipmaps,
                  "auto (default: box levels unless the file has its own), none, box, gaussian, edge, stored");
  cmd->add_option("--quality", c->quality,
                  "Encoder effort 0..100 (libastcenc; libsquish fit: <34 range, <67 cluster, else iterative)");
  cmd->add_option(
         "--out", c->out,
         "Output file: .dds (BC), .ktx (any format), .astc (ASTC, one level); other names: DDS for BC, else KTX")
      ->required();
  cmd->add_flag("--force", c->force, "Overwrite --out if it exists");
  cmd->callback([c] { run_compress(*c); });

  auto d = std::make_shared<DecompressOptions>();
  CLI::App* dec = app.add_subcommand("decompress", "Decode one level of a DDS, KTX or .astc file to an image");
  dec->add_option("file", d->in, "Block-compressed file (DDS, KTX 1.1, .astc; found by its magic)")->required();
  dec->add_option("--out", d->out, "Output image (PNG, ...)")->required();
  dec->add_option("--level", d->level, "MIP level to decode (default 0)");
  dec->add_flag("--force", d->force, "Overwrite --out if it exists");
  dec->callback([d] { run_decompress(*d); });
}

}  // namespace tfu::cli
