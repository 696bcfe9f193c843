// tfu mipmap: generate a MIP chain (box, Gaussian or edge-preserving) and write every level as PNG.
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/output_files.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct MipmapOptions {
  std::string texture;
  std::string method = "box";
  double alpha = 0.5;
  std::string out;
  bool force = false;
};

void run(const MipmapOptions& o) {
  const MipMethod method = mip_method_from_name(o.method);
  if (!(o.alpha >= 0.0 && o.alpha <= 1.0)) throw InputError(fmt::format("--alpha {} is outside [0, 1]", o.alpha));
  namespace fs = std::filesystem;
  if (o.out.empty()) throw InputError("--out: empty directory name");
  std::error_code ec;
  if (fs::exists(o.out, ec) && !fs::is_directory(o.out, ec))
    throw InputError(fmt::format("--out '{}' exists and is not a directory", quote_input(o.out)));
  Texture tex = *load_texture_spec({o.texture, {{"mipmaps", "none"}}}, "--texture").texture;
  generate_mipmaps(tex, method, o.alpha);
  // Every level file reserved before any is written (cmodel/output_files.hpp): nothing is
  // half-overwritten, and a failed run leaves no files and no new directory.
  OutputFiles outputs(o.force);
  std::vector<OutputFile*> files;
  for (int l = 0; l <= tex.max_level(); ++l)
    files.push_back(&outputs.add_image("--out", (fs::path(o.out) / fmt::format("level_{:02d}.png", l)).string()));
  for (int l = 0; l <= tex.max_level(); ++l) files[static_cast<size_t>(l)]->write_image(tex.levels[static_cast<size_t>(l)]);
  outputs.commit();
  for (int l = 0; l <= tex.max_level(); ++l) {
    const Image& img = tex.levels[static_cast<size_t>(l)];
    std::cout << fmt::format("level {:2d}  {:5d} x {:<5d} {}\n", l, img.width, img.height, files[static_cast<size_t>(l)]->path());
  }
}

}  // namespace

void register_mipmap(CLI::App& app) {
  auto o = std::make_shared<MipmapOptions>();
  CLI::App* cmd = app.add_subcommand("mipmap", "Generate a MIP chain and write every level as PNG");
  cmd->add_option("--texture", o->texture, "Base level: image file or proc:NAME[:SIZE]")->required();
  cmd->add_option("--method", o->method, "box (Lee & Jen Eq. 8), gaussian, edge (Eq. 7)");
  cmd->add_option("--alpha", o->alpha, "Edge-preserving weight alpha of Eq. 7 (0..1)");
  cmd->add_option("--out", o->out, "Output directory (level_00.png, level_01.png, ...)")->required();
  cmd->add_flag("--force", o->force, "Overwrite existing level files");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
