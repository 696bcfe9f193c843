// tfu kernel-error: the filter-kernel representation error eps_h of Hadwiger 2004, Eq. 3.5 /
// Table 3.5, for one configuration or the whole table beside the published values.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/kernel_error.hpp"
#include "sim/tfu/choices.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct KernelErrorOptions {
  KernelErrorSpec spec;
  std::string recon = "nearest";
  std::string sample_pos = "centre";
  std::string grid = "corner";
  std::string edge = "clamp";
  std::string composition = "separable";
  bool table = false;
  bool with_3d = false;
  double floor_lsb = 0;  // --floor: the quantizer error bound in LSB
};

void apply_choices(KernelErrorOptions& o) {
  o.spec.recon = parse_choice<RomRecon>("--recon", o.recon,
                                        {{"nearest", RomRecon::Nearest}, {"box", RomRecon::Nearest}, {"linear", RomRecon::Linear}});
  o.spec.sample_pos = parse_choice<SamplePos>("--sample-pos", o.sample_pos,
                                              {{"centre", SamplePos::Centre}, {"corner", SamplePos::Corner}});
  o.spec.grid = parse_choice<LocationGrid>("--grid", o.grid, {{"corner", LocationGrid::Corner}, {"centre", LocationGrid::Centre}});
  o.spec.composition = parse_choice<Composition>(
      "--composition", o.composition,
      {{"separable", Composition::Separable}, {"separable-fixed", Composition::SeparableFixed}, {"tiles", Composition::Tiles}});
  o.spec.edge = parse_choice<TileEdge>("--edge", o.edge, {{"clamp", TileEdge::Clamp}, {"continuous", TileEdge::Continuous}});
}

void print_table(const KernelErrorOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  fmt::print("Filter kernel error bounds 255*eps_h (Hadwiger 2004 Table 3.5 layout); b = {}, sample-pos {}, grid {}, edge {}, composition {}{}\n",
             o.spec.bits, o.sample_pos, o.grid, o.edge, o.composition, o.spec.requantize_linear ? ", requantize" : "");
  fmt::print("ours = this model, pub = published, diff = (ours - pub) / pub\n\n");
  fmt::print("| kernel | R | 2D box ours | pub | diff | 2D lin ours | pub | diff |{}\n",
             o.with_3d ? " 3D box ours | pub | diff | 3D lin ours | pub | diff |" : "");
  fmt::print("|---|---:|---:|---:|---:|---:|---:|---:|{}\n", o.with_3d ? "---:|---:|---:|---:|---:|---:|" : "");
  const auto& pub = published_table_3_5();
  for (const char* kernel : {"bspline", "catmull-rom", "blackman"}) {
    for (int R : {16, 32, 64, 128, 256, 512}) {
      std::string line = fmt::format("| {} | {} |", kernel, R);
      for (int dims : {2, 3}) {
        if (dims == 3 && !o.with_3d) continue;
        for (RomRecon recon : {RomRecon::Nearest, RomRecon::Linear}) {
          const PublishedKernelError* p = nullptr;
          for (const auto& e : pub)
            if (e.kernel == std::string(kernel) && e.samples == R && e.dims == dims && e.recon == recon) p = &e;
          if (!p) {
            line += " n/a | n/a | |";
            continue;
          }
          KernelErrorSpec s = o.spec;
          s.kernel = kernel;
          s.samples = R;
          s.dims = dims;
          s.recon = recon;
          const double ours = kernel_error_scaled(s);
          line += fmt::format(" {:.4f} | {:.4f} | {:+.1f}% |", ours, p->value, 100.0 * (ours - p->value) / p->value);
        }
      }
      fmt::print("{}\n", line);
      std::fflush(stdout);
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("\ncomputed in {:.2f} s\n", secs);
}

// --table --floor: per 2D entry, the discretization error and the floor no quantizer within
// `lsb` LSB can go below (kernel_error_floor), beside the published value.
void print_floor_table(const KernelErrorOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  fmt::print("Floor of 255*eps_h under Eq. 3.5 for ANY quantizer within {} LSB per stored weight (2D, composition {}, {}^2 "
             "locations, sample-pos {}, grid {}, edge {})\n",
             o.floor_lsb, o.composition, o.spec.effective_locations(), o.sample_pos, o.grid, o.edge);
  fmt::print("discr. = unquantized ROM (discretization only); a published value below the floor cannot come from Eq. 3.5 as written\n\n");
  fmt::print("| kernel | R | recon | discr. | floor | published | published below floor |\n|---|---:|---|---:|---:|---:|---|\n");
  for (const char* kernel : {"bspline", "catmull-rom", "blackman"})
    for (int R : {16, 32, 64, 128, 256, 512})
      for (RomRecon recon : {RomRecon::Nearest, RomRecon::Linear}) {
        const PublishedKernelError* p = nullptr;
        for (const auto& e : published_table_3_5())
          if (e.kernel == std::string(kernel) && e.samples == R && e.dims == 2 && e.recon == recon) p = &e;
        KernelErrorSpec s = o.spec;
        s.kernel = kernel;
        s.samples = R;
        s.dims = 2;
        s.recon = recon;
        const KernelErrorFloor f = kernel_error_floor(s, o.floor_lsb);
        fmt::print("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} | {} |\n", kernel, R, recon == RomRecon::Nearest ? "box" : "linear",
                   f.discretization, f.floor, p->value, p->value < f.floor ? "**yes**" : "no");
        std::fflush(stdout);
      }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("\ncomputed in {:.2f} s\n", secs);
}

}  // namespace

void register_kernel_error(CLI::App& app) {
  auto opts = std::make_shared<KernelErrorOptions>();
  auto* cmd = app.add_subcommand("kernel-error",
                                 "Filter-kernel ROM error eps_h x (2^b-1) (Hadwiger 2004 Eq. 3.5, Table 3.5); "
                                 "prints the value as the last line, or the whole table with --table");
  cmd->add_option("--kernel", opts->spec.kernel, "Kernel: bspline, catmull-rom, mitchell, kaiser, blackman, tent, box")
      ->capture_default_str();
  cmd->add_option("--samples", opts->spec.samples, "Samples per tile and dimension R (16..512)")->capture_default_str();
  cmd->add_option("--bits", opts->spec.bits, "Bits per ROM weight b (4..16)")->capture_default_str()->check(unsigned_integer(UINT32_MAX));
  cmd->add_option("--recon", opts->recon, "ROM reconstruction: nearest (box) or linear")->capture_default_str();
  cmd->add_option("--dims", opts->spec.dims, "Dimensions: 2 (1024^2 locations), 3 (256^3), or 1 (one set of weights, 1024 locations)")->capture_default_str();
  cmd->add_option("--locations", opts->spec.locations, "Resampling locations per dimension (0 = 1024 in 2D, 256 in 3D)")
      ->capture_default_str();
  cmd->add_option("--sample-pos", opts->sample_pos, "ROM sample positions in a tile: centre ((k+.5)/R) or corner (k/R)")
      ->capture_default_str();
  cmd->add_option("--grid", opts->grid, "Resampling locations: corner (i/N) or centre ((i+.5)/N)")->capture_default_str();
  cmd->add_option("--edge", opts->edge, "Linear reconstruction at tile edges: clamp or continuous")->capture_default_str();
  cmd->add_option("--composition", opts->composition,
                  "d-D weights: separable (product of quantized 1D weights), separable-fixed (through the b-bit "
                  "tile-weight multiplier) or tiles (quantized d-D tiles)")
      ->capture_default_str();
  cmd->add_flag("--requantize", opts->spec.requantize_linear,
                "Round linearly reconstructed weights back to b bits (a texture unit with b-bit output)");
  cmd->add_option("--threads", opts->spec.threads, "Worker threads (0 = all cores)")->capture_default_str();
  cmd->add_flag("--table", opts->table, "Print the whole Table 3.5 (2D) beside the published values");
  cmd->add_flag("--with-3d", opts->with_3d, "With --table: also the 3D columns (slow: minutes)");
  CLI::Option* floor_opt = cmd->add_option("--floor", opts->floor_lsb,
                  "Print the floor no quantizer within this many LSB per stored weight can go below (dims 1 or 2, "
                  "separable or tiles; with --table: the 2D table beside the published values)");
  cmd->callback([opts, floor_opt] {
    apply_choices(*opts);
    const bool floor = floor_opt->count() > 0;
    if (floor && !(opts->floor_lsb >= 0 && opts->floor_lsb <= 8))
      throw InputError(fmt::format("--floor must be in 0..8 LSB, got {}", opts->floor_lsb));
    if (opts->table) {
      opts->spec.validate();
      if (floor) {
        print_floor_table(*opts);
      } else {
        print_table(*opts);
      }
      return;
    }
    if (floor) {
      const KernelErrorFloor f = kernel_error_floor(opts->spec, opts->floor_lsb);
      fmt::print("kernel={} R={} b={} recon={} dims={} locations={}^{} sample-pos={} grid={} edge={}: discretization {:.4f}, "
                 "floor for quantizers within {} LSB\n",
                 opts->spec.kernel, opts->spec.samples, opts->spec.bits, opts->recon, opts->spec.dims,
                 opts->spec.effective_locations(), opts->spec.dims, opts->sample_pos, opts->grid, opts->edge,
                 f.discretization, opts->floor_lsb);
      fmt::print("{:.4f}\n", f.floor);
      return;
    }
    const double v = kernel_error_scaled(opts->spec);
    fmt::print("kernel={} R={} b={} recon={} dims={} locations={}^{} sample-pos={} grid={} edge={} composition={}\n", opts->spec.kernel,
               opts->spec.samples, opts->spec.bits, opts->recon, opts->spec.dims, opts->spec.effective_locations(),
               opts->spec.dims, opts->sample_pos, opts->grid, opts->edge, opts->composition);
    fmt::print("{:.4f}\n", v);
  });
}

}  // namespace tfu::cli
