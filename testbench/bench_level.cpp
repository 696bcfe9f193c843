// tfu_bench_level: speed of loading OpenArena levels (Google Benchmark, one thread): open the game
// archives, read and check the BSP, tessellate the patches, resolve and decode every texture with
// its box MIP chain, build the lightmaps.
//
// BM_LoadLevelCold/<level>: a new TextureCache per iteration (the first level of a run: every image
// decoded). BM_LoadLevelWarm/<level>: the cache kept across iterations (another spawn point or a
// reload within one run: no image decoded again). Target: a level and its
// textures load in under 3 s. Needs the game data (scripts/bootstrap; docs/real-frames.md).
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_level.hpp"

namespace tfu::q3 {
namespace {

const std::vector<std::string> kLevels = {"aggressor", "oa_dm5", "czest3ctf"};

void label(benchmark::State& state, const Level& l, size_t decoded) {
  state.SetLabel(fmt::format("{}: {} drawn faces, {} patches, {} triangles, {} textures decoded, {} lightmaps", l.name,
                             l.counts.faces_drawn, l.counts.patches, l.counts.triangles, decoded,
                             l.lightmaps.size() - 1));
}

void BM_LoadLevelCold(benchmark::State& state) {
  const std::string& name = kLevels[static_cast<size_t>(state.range(0))];
  try {
    size_t decoded = 0;
    for (auto _ : state) {
      const GameArchives archives(openarena_dir());
      TextureCache cache(archives);
      const Level l = load_level(archives, name, cache);
      decoded = cache.decoded();
      benchmark::DoNotOptimize(l.triangles.data());
      state.PauseTiming();
      label(state, l, decoded);
      state.ResumeTiming();
    }
  } catch (const InputError& e) {
    state.SkipWithError(e.what());
  }
}

void BM_LoadLevelWarm(benchmark::State& state) {
  const std::string& name = kLevels[static_cast<size_t>(state.range(0))];
  try {
    const GameArchives archives(openarena_dir());
    TextureCache cache(archives);
    load_level(archives, name, cache);  // fills the cache
    const size_t decoded = cache.decoded();
    for (auto _ : state) {
      const Level l = load_level(archives, name, cache);
      benchmark::DoNotOptimize(l.triangles.data());
      state.PauseTiming();
      label(state, l, cache.decoded() - decoded);
      state.ResumeTiming();
    }
  } catch (const InputError& e) {
    state.SkipWithError(e.what());
  }
}

BENCHMARK(BM_LoadLevelCold)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadLevelWarm)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace tfu::q3

BENCHMARK_MAIN();
