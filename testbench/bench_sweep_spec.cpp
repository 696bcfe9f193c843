// tfu_bench_sweep: speed of checking a sweep spec (Google Benchmark, one thread), side by side with
// nlohmann's parse of the same text, so the ratio says what the spec's own checks (types, ranges,
// duplicates) cost beyond reading JSON.
//
// BM_JsonParse/N:       nlohmann::ordered_json::parse of a spec whose one grid key lists N values.
// BM_ParseSpecGrid/N:   tfu::sweep::parse_spec of the same text: the JSON parse plus every value's type and
//                       range check and the duplicate check (a hash set, TFU-S E10: it was quadratic,
//                       10^5 values took 17 s). Target: 10^6 values, the documented limit, in under 1 s.
// BM_ParseSpecScenes/N: a "scenes" list of N distinct names (the list check only; opening the scenes is
//                       expand()'s work and is not measured here).
#include <string>

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sim/sweep/sweep_spec.hpp"

namespace {

std::string grid_spec(int64_t n) {
  std::string s = R"({"scenes": ["ground_plane"], "grid": {"memory.latency": [)";
  for (int64_t i = 0; i < n; ++i) s += fmt::format("{}{}", i ? "," : "", i);
  return s + "]}}";
}

std::string scenes_spec(int64_t n) {
  std::string s = R"({"scenes": [)";
  for (int64_t i = 0; i < n; ++i) s += fmt::format("{}\"scene_{}.json\"", i ? "," : "", i);
  return s + R"(], "grid": {"memory.latency": [100]}})";
}

void BM_JsonParse(benchmark::State& state) {
  const std::string text = grid_spec(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(nlohmann::ordered_json::parse(text));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_ParseSpecGrid(benchmark::State& state) {
  const std::string text = grid_spec(state.range(0));
  size_t values = 0;
  for (auto _ : state) values = tfu::sweep::parse_spec(text, "bench.json").grid_values.front().size();
  if (values != static_cast<size_t>(state.range(0))) state.SkipWithError("the spec lost values");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_ParseSpecScenes(benchmark::State& state) {
  const std::string text = scenes_spec(state.range(0));
  size_t scenes = 0;
  for (auto _ : state) scenes = tfu::sweep::parse_spec(text, "bench.json").scenes.size();
  if (scenes != static_cast<size_t>(state.range(0))) state.SkipWithError("the spec lost scenes");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_JsonParse)->RangeMultiplier(10)->Range(10000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParseSpecGrid)->RangeMultiplier(10)->Range(10000, 1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ParseSpecScenes)->RangeMultiplier(10)->Range(10000, 1000000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
