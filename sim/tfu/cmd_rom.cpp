// tfu rom: dump any ROM (tile-weight or Lee & Jen direction-weight) as CSV or $readmemh hex.
#include <bit>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cmodel/direction_rom.hpp"
#include "cmodel/error.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/rom_dump.hpp"
#include "sim/tfu/choices.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct RomOptions {
  std::string kind = "tile";
  std::string kernel = "catmull-rom";
  int samples = 64;
  unsigned bits = 8;
  std::string pos = "centre";
  std::string rounding = "sum";
  std::string dir = "all";
  std::string format = "csv";
  std::string out;
  bool force = false;
  bool list = false;
};

void list_directions(std::ostream& os) {
  using namespace lee_jen;
  const auto& shapes = kernel_shapes();
  os << "| index | direction | family | Cp | Cq | ROI | t |";
  for (const auto& s : shapes) os << ' ' << s.name() << " |";
  os << "\n|---:|---|---|---|---|---:|---|";
  for (size_t i = 0; i < shapes.size(); ++i) os << "---|";
  os << '\n';
  for (const Direction& d : directions()) {
    os << fmt::format("| {} | {} | {} | C{} | C{} | {:.4f} | {} |", d.index, d.name(), d.family(), d.p, d.q, d.roi,
                      d.axis == BlendAxis::X ? "xf" : "yf");  // the paper's names of fu, fv
    for (const auto& s : shapes) os << (usable_directions(s.mask) >> d.index & 1u ? " yes |" : " - |");
    os << '\n';
  }
  os << "| | usable directions | | | | | |";
  for (const auto& s : shapes) os << ' ' << std::popcount(usable_directions(s.mask)) << " |";
  os << "\n\n";
  // Per shape: the missing texels and the directions that need them.
  for (const auto& s : shapes) {
    os << fmt::format("{}: {} texels, {} directions", s.name(), std::popcount(static_cast<unsigned>(s.mask)),
                      std::popcount(usable_directions(s.mask)));
    std::string missing, dropped;
    for (int n = 1; n <= kTexels; ++n)
      if (!(s.mask >> (n - 1) & 1u)) missing += fmt::format("{}C{}", missing.empty() ? "" : " ", n);
    const uint32_t usable = usable_directions(s.mask);
    for (const Direction& d : directions())
      if (!(usable >> d.index & 1u)) dropped += fmt::format("{}{}", dropped.empty() ? "" : " ", d.name());
    if (!missing.empty()) os << "; missing " << missing << "; drops " << dropped;
    os << '\n';
  }
}

int parse_dir(const std::string& s) {
  if (s == "all") return -1;
  std::size_t used = 0;
  int d = -2;
  try {
    d = std::stoi(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || d < 0 || d >= lee_jen::kDirections)
    throw InputError("--dir must be 0..21 or 'all', got '" + s + "'");
  return d;
}

void run(const RomOptions& o) {
  enum class Kind { Tile, Direction };
  enum class Format { Csv, Hex };
  const Kind kind = parse_choice<Kind>("--kind", o.kind, {{"tile", Kind::Tile}, {"direction", Kind::Direction}});
  const Format format = parse_choice<Format>("--format", o.format, {{"csv", Format::Csv}, {"hex", Format::Hex}});
  if (o.list && kind != Kind::Direction) throw InputError("--list needs --kind direction (got --kind " + o.kind + ")");
  std::unique_ptr<TileWeightRom> tile;
  int dir = -1;
  if (kind == Kind::Tile) {
    TileRomSpec spec;
    spec.samples = o.samples;
    spec.bits = o.bits;
    spec.pos = parse_choice<SamplePos>("--pos", o.pos, {{"centre", SamplePos::Centre}, {"corner", SamplePos::Corner}});
    spec.rounding = parse_choice<RomRounding>("--rounding", o.rounding,
                                              {{"sum", RomRounding::SumPreserving}, {"nearest", RomRounding::Nearest}});
    spec.validate();                                      // R, b out of range -> InputError
    const FilterKernel kernel = FilterKernel::by_name(o.kernel);  // unknown name -> InputError
    tile = std::make_unique<TileWeightRom>(kernel, spec);
  } else {
    dir = parse_dir(o.dir);
  }

  OutputFiles outputs(o.force);
  std::ostream* os = o.out.empty() ? &std::cout : &outputs.add("--out", o.out).stream();
  if (o.list) {
    list_directions(*os);
  } else if (tile) {
    format == Format::Csv ? dump_tile_rom_csv(*tile, *os) : dump_tile_rom_hex(*tile, *os);
  } else {
    format == Format::Csv ? dump_direction_rom_csv(dir, *os) : dump_direction_rom_hex(dir, *os);
  }
  outputs.commit();
  if (!o.out.empty()) print_summary_line("tfu rom: wrote " + o.out);
}

}  // namespace

void register_rom(CLI::App& app) {
  auto o = std::make_shared<RomOptions>();
  auto* cmd = app.add_subcommand("rom", "Dump a ROM as CSV or as hex for $readmemh (tile-weight or Lee & Jen direction-weight)");
  cmd->add_option("--kind", o->kind, "tile or direction")->capture_default_str();
  cmd->add_option("--kernel", o->kernel, "tile: kernel (bspline, catmull-rom, mitchell, kaiser, blackman, tent, box)")
      ->capture_default_str();
  cmd->add_option("--samples", o->samples, "tile: samples per tile R (16..512)")->capture_default_str();
  cmd->add_option("--bits", o->bits, "tile: magnitude bits b (4..16)")->capture_default_str()->check(unsigned_integer(UINT32_MAX));
  cmd->add_option("--pos", o->pos, "tile: sample positions centre ((k+.5)/R) or corner (k/R)")->capture_default_str();
  cmd->add_option("--rounding", o->rounding, "tile: sum (sum-preserving rows) or nearest (Eq. 3.4)")->capture_default_str();
  cmd->add_option("--dir", o->dir, "direction: index 0..21 or all")->capture_default_str();
  cmd->add_flag("--list", o->list, "direction: print the table of the 22 directions and kernel shapes");
  cmd->add_option("--format", o->format, "csv or hex")->capture_default_str();
  cmd->add_option("--out", o->out, "Output file (default: stdout)");
  cmd->add_flag("--force", o->force, "Overwrite --out if it exists");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
