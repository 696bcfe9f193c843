// The shared run helpers of both engines (rtl/unit_wiring.hpp declares them): what the unit refuses
// before it starts, the statistics of a finished run, and the rates derived from its counters.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_output.hpp"
#include "rtl/unit_stats.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {
namespace detail {

// check_inputs and derive_stats: rtl/unit_wiring.hpp.
void check_inputs(const Frame& frame, const Trace& trace, const UnitConfig& u) {
  u.validate();
  frame.regs.validate();
  if (frame.line_bytes != u.cache.line_bytes)
    throw InputError(fmt::format("the frame's textures are tiled for {}-byte lines, the cache has {}-byte lines",
                                 frame.line_bytes, u.cache.line_bytes));
  if (trace.mode == TraceMode::Quad && trace.requests.size() % 4 != 0)
    throw InputError("a quad trace needs a multiple of 4 requests");
  const size_t nt = frame.regs.textures.size(), ns = frame.regs.samplers.size();
  std::vector<uint8_t> seen(nt * ns, 0);
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const TraceRequest& r = trace.requests[i];
    if (r.texture >= nt || r.sampler >= ns)
      throw InputError(fmt::format("request {} names texture {} and sampler {}; {} and {} are bound", i, r.texture,
                                   r.sampler, nt, ns));
    uint8_t& s = seen[r.texture * ns + r.sampler];
    if (s) continue;
    s = 1;
    const SamplerDescriptor& smp = frame.regs.samplers[r.sampler];
    const TexelFormat f = frame.regs.textures[r.texture].format;
    if (!filters_format(smp.mode.base, f))
      throw InputError(fmt::format("request {}: sampler {} ({}) is not defined on texture {} ({})", i, r.sampler,
                                   filter_mode_name(smp.mode), r.texture, texel_format_name(f)));
    const bool wants = smp.mode.base == BaseFilter::Cubic && smp.kernel == kBsplineInterp;
    if (wants != (frame.regs.textures[r.texture].content == TextureContent::BsplineCoefficients))
      throw InputError(fmt::format(
          "request {}: sampler {} ({} {}) and texture {} ({}) do not go together (bind_requests)", i, r.sampler,
          filter_mode_name(smp.mode), smp.kernel, r.texture, wants ? "texels" : "B-spline coefficients"));
  }
}

void derive_stats(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, Unit& u, UnitOutput& out) {
  sim::Stats& st = out.stats;
  const size_t n = trace.requests.size();
  u.cache_stage.publish(st);
  u.address_gen.publish(st);
  add(st, UnitStat::Cycles, out.cycles);
  add(st, UnitStat::Pixels, n);
  add(st, UnitStat::MemoryBytes, u.mem.bytes_read());
  add(st, UnitStat::MemoryRequests, u.mem.requests());
  if (u.filter) add(st, UnitStat::FilterLaneBusyCycles, u.filter->busy_cycles());
  if (u.edge_direction) st.set_histogram(stat_key(UnitStat::EdgeDirection), std::vector<uint64_t>(u.edge_direction->chosen.begin(), u.edge_direction->chosen.end()));
  st.set_histogram(stat_key(UnitStat::Latency), u.response.latency);
  // Traffic per texture descriptor and per material stage.
  std::vector<uint64_t> tex_requests(frame.textures.size(), 0);
  std::array<uint64_t, 4> stage_requests{};
  for (const TraceRequest& r : trace.requests) {
    ++tex_requests[r.texture];
    ++stage_requests[r.stage];
  }
  sim::Stats::Table textures{{"index", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t t = 0; t < frame.textures.size(); ++t) {
    const int ti = static_cast<int>(t);
    if (tex_requests[t] == 0 && u.cache.texture_hits(ti) + u.cache.texture_misses(ti) == 0) continue;
    textures.rows.emplace_back(fmt::format("{} {}", t, frame.textures[t].name),
                               std::vector<uint64_t>{t, tex_requests[t], u.cache.texture_hits(ti),
                                                     u.cache.texture_misses(ti), u.mem.texture_bytes(ti)});
  }
  st.set_table(stat_key(UnitStat::Textures), std::move(textures));
  if (u.cache_stage.any_compressed()) {
    sim::Stats::Table decoders{{"index", "decoded_blocks", "decoder_busy_cycles", "decoder_stall_cycles"}, {}};
    for (size_t t = 0; t < frame.textures.size(); ++t) {
      const int ti = static_cast<int>(t);
      if (!frame.regs.textures[t].compressed || tex_requests[t] == 0) continue;
      decoders.rows.emplace_back(
          fmt::format("{} {}", t, frame.textures[t].name),
          std::vector<uint64_t>{t, u.cache_stage.decoded_blocks(ti), u.cache_stage.decoder_busy(ti),
                                u.cache_stage.decoder_stall(ti)});
    }
    st.set_table(stat_key(UnitStat::Decoders), std::move(decoders));
  }
  sim::Stats::Table stages{{"stage", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t k = 0; k < 4; ++k)
    if (stage_requests[k] > 0)
      stages.rows.emplace_back(
          fmt::format("stage {}", k),
          std::vector<uint64_t>{k, stage_requests[k], u.cache_stage.stage_hits[k], u.cache_stage.stage_misses[k],
                                u.cache_stage.stage_misses[k] * static_cast<uint64_t>(ucfg.cache.line_bytes)});
  st.set_table(stat_key(UnitStat::Stages), std::move(stages));
  derive_rates(st, n, out.cycles);
}

}  // namespace detail

const char* unit_engine_name(UnitEngine e) { return kUnitEngineNames.name(e); }
UnitEngine unit_engine_from_name(const std::string& name) { return kUnitEngineNames.from_name(name); }

void derive_rates(sim::Stats& st, size_t requests, uint64_t cycles) {
  const auto n = static_cast<double>(requests);
  set(st, UnitStat::PixelsPerClock, cycles ? n / static_cast<double>(cycles) : 0.0);
  set(st, UnitStat::MemoryBytesPerPixel, requests ? static_cast<double>(counter(st, UnitStat::MemoryBytes)) / n : 0.0);
  set(st, UnitStat::ProbesPerPixel, requests ? static_cast<double>(counter(st, UnitStat::Probes)) / n : 0.0);
  const uint64_t h = counter(st, UnitStat::CacheLineHits), m = counter(st, UnitStat::CacheLineMisses);
  set(st, UnitStat::CacheHitRate, h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0);
  uint64_t lat_sum = 0, lat_min = UINT64_MAX, lat_max = 0;
  if (const std::vector<uint64_t>* lat = st.histogram(stat_key(UnitStat::Latency)))
    for (size_t c = 0; c < lat->size(); ++c)
      if ((*lat)[c]) {
        lat_sum += c * (*lat)[c];
        lat_min = std::min<uint64_t>(lat_min, c);
        lat_max = c;
      }
  set(st, UnitStat::LatencyMean, requests ? static_cast<double>(lat_sum) / n : 0.0);
  set(st, UnitStat::LatencyMin, requests ? static_cast<double>(lat_min) : 0.0);
  set(st, UnitStat::LatencyMax, static_cast<double>(lat_max));
}

}  // namespace tfu::rtl
