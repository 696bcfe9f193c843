// tfu formats: measures the number formats' errors and prints them beside the analytic bounds, as
// Markdown tables (optionally also as JSON).
//   unorm b = 8, 12 (cmodel/unorm.hpp): exhaustive over all operand pairs, mul_round against
//     Hadwiger 2004 Eq. 3.9, mul_trunc against Eq. 3.8, and the division-free forms against
//     mul_round (mul8_divfree over all 65,536 pairs of b = 8).
//   Vs16 (cmodel/signed_formats.hpp, Strzodka 2002 Sec. 3.2, 3.3): add/sub (must be exact where it
//     does not saturate) and multiply (against 382/255 LSB) over --pairs random pairs (fixed seed,
//     std::mt19937_64), or over all 2^32 pairs with --exhaustive.
// Exit codes: 0, 1 if a measured error exceeds its bound (after printing), 2 for bad input.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <atomic>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/signed_formats.hpp"
#include "cmodel/unorm.hpp"
#include "sim/tfu/choices.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

inline constexpr int64_t kMaxPairs = 1'000'000'000;

struct FormatsOptions {
  int64_t pairs = 10'000'000;
  uint64_t seed = 2002;
  bool exhaustive = false;
  std::string json;
  bool force = false;
};

// ------------------------------------------------------------------------------------ unorm
struct UnormRow {
  unsigned bits = 0;
  uint64_t pairs = 0;
  uint64_t round_err_num = 0;  // max |m * mul_round(x, y) - x y|; error in [0, 1] = num / m^2
  uint64_t trunc_err_num = 0;  // max |m * mul_trunc(x, y) - x y|
  uint64_t divfree_mismatches = 0;   // mul_divfree != mul_round
  uint64_t divfree8_mismatches = 0;  // mul8_divfree != mul_round (b = 8 only)
};

UnormRow measure_unorm(unsigned bits) {
  UnormRow row;
  row.bits = bits;
  const uint64_t m = unorm::max_code(bits);
  for (uint32_t x = 0; x <= m; ++x)
    for (uint32_t y = 0; y <= m; ++y) {
      const uint64_t p = uint64_t{x} * y;
      const uint32_t q = unorm::mul_round(x, y, bits), t = unorm::mul_trunc(x, y, bits);
      const uint64_t mq = m * q, mt = m * t;
      row.round_err_num = std::max(row.round_err_num, mq > p ? mq - p : p - mq);
      row.trunc_err_num = std::max(row.trunc_err_num, mt > p ? mt - p : p - mt);
      row.divfree_mismatches += unorm::mul_divfree(x, y, bits) != q;
      if (bits == 8) row.divfree8_mismatches += unorm::mul8_divfree(x, y) != q;
    }
  row.pairs = (m + 1) * (m + 1);
  return row;
}

// ------------------------------------------------------------------------------------ Vs16
struct Vs16Stats {
  uint64_t pairs = 0;
  int64_t add_max_err = 0;         // over non-saturating results, numerator LSBs
  uint64_t add_mismatches = 0;     // wrong value, or wrong code on saturation
  uint64_t add_saturated = 0;
  int64_t mul_max_err_scaled = 0;  // max |32640 * mul - clamp(v1 v2)|, units of 1/32640 LSB
  uint64_t mul_over_bound = 0;
  snorm::Vs16 mul_worst_x{}, mul_worst_y{};

  void check(snorm::Vs16 x, snorm::Vs16 y) {
    ++pairs;
    const int64_t v1 = snorm::to_numerator(x), v2 = snorm::to_numerator(y);
    for (int s : {+1, -1}) {
      const int64_t want = v1 + s * v2;
      const snorm::Vs16 got = snorm::add_sub(x, y, s);
      if (want > snorm::kVs16Max || want < snorm::kVs16Min) {
        ++add_saturated;
        add_mismatches += got != (want > 0 ? snorm::kMaxCode : snorm::kMinCode);
      } else {
        const int64_t e = std::abs(snorm::to_numerator(got) - want);
        add_max_err = std::max(add_max_err, e);
        add_mismatches += e != 0;
      }
    }
    constexpr int64_t kLo = int64_t{snorm::kVs16Min} * snorm::kVs16Denominator;
    constexpr int64_t kHi = int64_t{snorm::kVs16Max} * snorm::kVs16Denominator;
    const int64_t exact = std::clamp(v1 * v2, kLo, kHi);
    const int64_t e = std::abs(int64_t{snorm::kVs16Denominator} * snorm::to_numerator(snorm::mul(x, y)) - exact);
    if (e > mul_max_err_scaled) {
      mul_max_err_scaled = e;
      mul_worst_x = x;
      mul_worst_y = y;
    }
    mul_over_bound += e > snorm::kVs16MulErrorBoundScaled;
  }

  void merge(const Vs16Stats& o) {
    pairs += o.pairs;
    add_max_err = std::max(add_max_err, o.add_max_err);
    add_mismatches += o.add_mismatches;
    add_saturated += o.add_saturated;
    if (o.mul_max_err_scaled > mul_max_err_scaled) {
      mul_max_err_scaled = o.mul_max_err_scaled;
      mul_worst_x = o.mul_worst_x;
      mul_worst_y = o.mul_worst_y;
    }
    mul_over_bound += o.mul_over_bound;
  }
};

snorm::Vs16 code_of(uint32_t bits16) {
  return snorm::Vs16{static_cast<uint8_t>(bits16 >> 8), static_cast<uint8_t>(bits16 & 0xFF)};
}

Vs16Stats measure_vs16_random(int64_t pairs, uint64_t seed) {
  Vs16Stats st;
  std::mt19937_64 rng(seed);
  for (int64_t i = 0; i < pairs; ++i) {
    const uint64_t b = rng();
    st.check(code_of(static_cast<uint32_t>(b & 0xFFFF)), code_of(static_cast<uint32_t>(b >> 16 & 0xFFFF)));
  }
  return st;
}

// All 2^32 (x, y) pairs, x split across threads.
Vs16Stats measure_vs16_exhaustive() {
  snorm::multiplication_table();  // build the table before the threads start
  const int n = hardware_threads();
  std::vector<Vs16Stats> part(static_cast<size_t>(n));
  std::atomic<uint32_t> next{0};
  run_workers(n, [&](int t) {
    for (uint32_t i = next++; i < 65536; i = next++)
      for (uint32_t j = 0; j < 65536; ++j) part[static_cast<size_t>(t)].check(code_of(i), code_of(j));
  });
  Vs16Stats st;
  for (const auto& p : part) st.merge(p);
  return st;
}

std::string code_str(snorm::Vs16 x) { return fmt::format("({}, {})", x.r, x.a); }

void run(const FormatsOptions& o) {
  if (o.pairs < 1 || o.pairs > kMaxPairs)
    throw InputError(fmt::format("--pairs must be in [1, {}], got {}", kMaxPairs, o.pairs));
  OutputFiles outputs(o.force);
  OutputFile* json_file = o.json.empty() ? nullptr : &outputs.add("--json", o.json);
  nlohmann::json out;
  bool ok = true;

  fmt::print("## unorm normalized multiply, exhaustive over all operand pairs (Hadwiger 2004 Eq. 3.7-3.9)\n\n");
  fmt::print("Errors in the [0, 1] domain. mul_round is Eq. 3.7; the bounds are eps_m_round (Eq. 3.9) and "
             "eps_m_trunc (Eq. 3.8) from cmodel/unorm.hpp.\n\n");
  fmt::print("| b | pairs | max error mul_round | Eq. 3.9 bound | max error mul_trunc | Eq. 3.8 bound | within bounds "
             "| mul8_divfree == mul_round | mul_divfree == mul_round |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---|---|---|\n");
  for (unsigned b : {8u, 12u}) {
    const UnormRow row = measure_unorm(b);
    const double m2 = static_cast<double>(unorm::max_code(b)) * unorm::max_code(b);
    const double er = static_cast<double>(row.round_err_num) / m2, et = static_cast<double>(row.trunc_err_num) / m2;
    const double br = unorm::eps_m_round(b), bt = unorm::eps_m_trunc(b);
    const bool within = er <= br * (1 + 1e-12) && et <= bt * (1 + 1e-12);
    const bool divfree_ok = row.divfree_mismatches == 0 && row.divfree8_mismatches == 0;
    ok = ok && within && divfree_ok;
    const std::string d8 = b == 8 ? fmt::format("{} of {} pairs", row.pairs - row.divfree8_mismatches, row.pairs) : "n/a";
    fmt::print("| {} | {} | {:.9f} | {:.9f} | {:.9f} | {:.9f} | {} | {} | {} of {} pairs |\n", b, row.pairs, er, br, et, bt,
               within ? "yes" : "NO", d8, row.pairs - row.divfree_mismatches, row.pairs);
    nlohmann::json j = {{"bits", b},
                        {"pairs", row.pairs},
                        {"mul_round_max_error", er},
                        {"eq3_9_bound", br},
                        {"mul_trunc_max_error", et},
                        {"eq3_8_bound", bt},
                        {"within_bounds", within},
                        {"mul_divfree_mismatches", row.divfree_mismatches}};
    if (b == 8) j["mul8_divfree_mismatches"] = row.divfree8_mismatches;
    out["unorm"].push_back(j);
  }

  const Vs16Stats st = o.exhaustive ? measure_vs16_exhaustive() : measure_vs16_random(o.pairs, o.seed);
  const double lsb = snorm::kVs16Denominator;
  const double mul_err = static_cast<double>(st.mul_max_err_scaled) / lsb;
  ok = ok && st.add_mismatches == 0 && st.mul_over_bound == 0;
  fmt::print("\n## Strzodka composite signed 16-bit (Vs16), {}\n\n",
             o.exhaustive ? "exhaustive over all 2^32 operand pairs"
                          : fmt::format("{} random operand pairs (std::mt19937_64, seed {})", st.pairs, o.seed));
  fmt::print("Errors in numerator LSBs (1 LSB = 1/32640) against the exact result of the decoded operands (clamped "
             "to the word's range). add/sub is checked for s = +1 and -1: exact unless the result leaves "
             "[-32768, 32767]; {} of the {} results did and must be the extreme code (0, 0) or (255, 255).\n\n",
             st.add_saturated, 2 * st.pairs);
  fmt::print("| operation | pairs | max error (LSB) | analytic bound (LSB) | failures |\n");
  fmt::print("|---|---:|---:|---:|---|\n");
  fmt::print("| Vs16 add/sub (one carry check, Sec. 3.2) | {} | {} | 0 (exact) | {} mismatches |\n", st.pairs,
             st.add_max_err, st.add_mismatches);
  fmt::print("| Vs16 multiply (table M + rounded mixed term, lo*lo dropped, Sec. 3.3) | {} | {:.6f} | {:.6f} (382/255) "
             "| {} over bound |\n",
             st.pairs, mul_err, snorm::kVs16MulErrorBound, st.mul_over_bound);
  fmt::print("\nWorst multiply: {} * {} = {} LSB ({} / 32640 LSB).\n", code_str(st.mul_worst_x), code_str(st.mul_worst_y),
             fmt::format("{:.6f}", mul_err), st.mul_max_err_scaled);
  out["vs16"] = {{"mode", o.exhaustive ? "exhaustive" : "random"},
                 {"pairs", st.pairs},
                 {"add_sub_max_error_lsb", st.add_max_err},
                 {"add_sub_mismatches", st.add_mismatches},
                 {"add_sub_saturated", st.add_saturated},
                 {"mul_max_error_lsb", mul_err},
                 {"mul_max_error_scaled", st.mul_max_err_scaled},
                 {"mul_bound_lsb", snorm::kVs16MulErrorBound},
                 {"mul_bound_scaled", snorm::kVs16MulErrorBoundScaled},
                 {"mul_over_bound", st.mul_over_bound},
                 {"mul_worst_pair", {{st.mul_worst_x.r, st.mul_worst_x.a}, {st.mul_worst_y.r, st.mul_worst_y.a}}}};
  if (!o.exhaustive) out["vs16"]["seed"] = o.seed;

  if (json_file) {
    json_file->stream() << json_dump(out, 2) << '\n';
    outputs.commit();
    print_summary_line(fmt::format("tfu formats: wrote {}", o.json));
  }
  std::fflush(stdout);
  if (!ok) throw CheckFailed("formats: a measured error exceeds its analytic bound (see the tables)");
}

}  // namespace

void register_formats(CLI::App& app) {
  auto o = std::make_shared<FormatsOptions>();
  auto* cmd = app.add_subcommand(
      "formats",
      "Measure the number formats' error bounds and print them as Markdown tables beside the analytic bounds: unorm "
      "b = 8 and 12 multiply (exhaustive; Hadwiger Eq. 3.8/3.9, division-free forms) and Strzodka's composite signed "
      "16-bit (Vs16) add/sub and multiply (random pairs, or all 2^32 with --exhaustive). Exit 1 if a bound is exceeded.");
  auto* pairs = cmd->add_option("--pairs", o->pairs, fmt::format("Random Vs16 operand pairs (1..{})", kMaxPairs))
                    ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the std::mt19937_64 pair generator")->capture_default_str()->check(unsigned_integer());
  cmd->add_flag("--exhaustive", o->exhaustive, "Check all 2^32 Vs16 pairs instead (multi-threaded, ~40 s on 2 cores)")
      ->excludes(pairs);
  cmd->add_option("--json", o->json, "Also write the figures as JSON to this file");
  cmd->add_flag("--force", o->force, "Overwrite --json if it exists");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
