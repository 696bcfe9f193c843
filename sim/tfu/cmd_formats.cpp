// tfu formats: measures the number formats' error bounds and prints them beside the analytic ones
// (Hadwiger 2004 Eq. 3.8-3.11; Strzodka 2002 Sec. 3.2-3.3).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/signed_formats.hpp"
#include "cmodel/unorm.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct FormatsOptions {
  long long pairs = 10'000'000;
  std::string json;
  bool force = false;
};

void run(const FormatsOptions& o) {
  if (o.pairs < 1 || o.pairs > 1'000'000'000LL)
    throw InputError("--pairs must be in [1, 1e9], got " + std::to_string(o.pairs));
  if (!o.json.empty() && std::filesystem::exists(o.json) && !o.force)
    throw InputError("--json '" + o.json + "' already exists (use --force to overwrite)");
  nlohmann::json out;

  fmt::print("## unorm normalized multiply (exhaustive over all pairs)\n\n");
  fmt::print("| b | pairs | max err round (LSB) | Eq. 3.9 | max err trunc (LSB) | Eq. 3.8 | divfree == round |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---|\n");
  for (unsigned b : {8u, 12u}) {
    const double m = unorm::max_code(b);
    double wr = 0.0, wt = 0.0;
    bool divfree_ok = true;
    for (uint32_t x = 0; x <= unorm::max_code(b); ++x)
      for (uint32_t y = 0; y <= unorm::max_code(b); ++y) {
        const double exact = static_cast<double>(x) * y / m;
        wr = std::max(wr, std::abs(unorm::mul_round(x, y, b) - exact));
        wt = std::max(wt, std::abs(unorm::mul_trunc(x, y, b) - exact));
        divfree_ok = divfree_ok && unorm::mul_divfree(x, y, b) == unorm::mul_round(x, y, b) &&
                     (b != 8 || unorm::mul8_divfree(x, y) == unorm::mul_round(x, y, b));
      }
    const double pairs = (m + 1) * (m + 1);
    fmt::print("| {} | {:.0f} | {:.6f} | {:.6f} | {:.6f} | {:.6f} | {} |\n", b, pairs, wr, unorm::eps_m_round(b) * m, wt,
               unorm::eps_m_trunc(b) * m, divfree_ok ? "yes" : "NO");
    out["unorm"][std::to_string(b)] = {{"max_err_round_lsb", wr},        {"eq3_9_lsb", unorm::eps_m_round(b) * m},
                                       {"max_err_trunc_lsb", wt},        {"eq3_8_lsb", unorm::eps_m_trunc(b) * m},
                                       {"divfree_equals_round", divfree_ok}, {"eps_m_round", unorm::eps_m_round(b)}};
  }

  std::mt19937_64 rng(2002);
  long long add_bad = 0, mul_n = 0;
  double mul_worst = 0.0;
  for (long long i = 0; i < o.pairs; ++i) {
    const uint64_t r = rng();
    const snorm::Vs16 x{static_cast<uint8_t>(r), static_cast<uint8_t>(r >> 8)}, y{static_cast<uint8_t>(r >> 16), static_cast<uint8_t>(r >> 24)};
    for (int s : {+1, -1}) {
      const long long want = static_cast<long long>(snorm::numerator(x)) + s * snorm::numerator(y);
      if (want >= snorm::kVs16Min && want <= snorm::kVs16Max && snorm::numerator(snorm::add_sub(x, y, s)) != want) ++add_bad;
    }
    const double exact = static_cast<double>(snorm::numerator(x)) * snorm::numerator(y) / snorm::kVs16Denominator;
    if (std::abs(exact) <= snorm::kVs16Max) {
      mul_worst = std::max(mul_worst, std::abs(snorm::numerator(snorm::mul(x, y)) - exact));
      ++mul_n;
    }
  }
  fmt::print("\n## Strzodka composite signed 16-bit (random pairs, seed 2002)\n\n");
  fmt::print("| operation | pairs | max error (LSB = 1/32640) | bound |\n|---|---:|---:|---:|\n");
  fmt::print("| add/sub (carry scheme) | {} | {} mismatches | exact |\n", o.pairs, add_bad);
  fmt::print("| multiply (hi*hi table + mixed, lo*lo dropped) | {} | {:.6f} | {:.6f} |\n", mul_n, mul_worst, snorm::kMulErrorBound);
  out["vs16"] = {{"pairs", o.pairs}, {"add_sub_mismatches", add_bad}, {"mul_max_err_lsb", mul_worst}, {"mul_bound_lsb", snorm::kMulErrorBound}};

  if (!o.json.empty()) {
    std::ofstream f(o.json);
    if (!f) throw InputError("cannot write --json '" + o.json + "'");
    f << out.dump(2) << '\n';
    fmt::print("\nwrote {}\n", o.json);
  }
  if (add_bad != 0 || mul_worst > snorm::kMulErrorBound) throw std::runtime_error("a measured error exceeds its bound");
}

}  // namespace

void register_formats(CLI::App& app) {
  auto o = std::make_shared<FormatsOptions>();
  auto* cmd = app.add_subcommand("formats", "Measure the number formats' error bounds (unorm multiply Eq. 3.8/3.9, "
                                            "Strzodka 16-bit add and multiply) and print them beside the analytic bounds");
  cmd->add_option("--pairs", o->pairs, "Random operand pairs for the 16-bit composite format (1..1e9)")->capture_default_str();
  cmd->add_option("--json", o->json, "Also write the figures as JSON to this file");
  cmd->add_flag("--force", o->force, "Overwrite --json if it exists");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
