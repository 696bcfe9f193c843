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
void check_config(const Frame& frame, const UnitConfig& u) {
  u.validate();
  frame.regs.validate();
  if (frame.line_bytes != u.cache.line_bytes)
    throw InputError(fmt::format("the frame's textures are tiled for {}-byte lines, the cache has {}-byte lines",
                                 frame.line_bytes, u.cache.line_bytes));
}

void check_inputs(const Frame& frame, const Trace& trace, const UnitConfig& u) {
  check_config(frame, u);
  if (trace.mode == TraceMode::Quad && trace.requests.size() % 4 != 0)
    throw InputError("a quad trace needs a multiple of 4 requests");
  check_requests(frame, trace.requests.data(), trace.requests.size(), 0);
}

void Unit::drain_to(size_t end, const UnitChunkSink* sink) {
  // The statistics, then the chunk's copies (each a run or two of its ring: software speed only).
  retire_stats.add_range(source, exit_cycle, accept, drained, end);
  if (sink != nullptr) {
    const size_t k = end - drained;
    chunk.first = drained;
    chunk.trace.mode = source.mode();
    chunk.trace.requests.resize(k);
    chunk.out.pixels.resize(k);
    chunk.out.response_cycle.resize(k);
    source.copy_out(drained, k, chunk.trace.requests.data());
    pixels.copy_out(drained, k, chunk.out.pixels.data());
    exit_cycle.copy_out(drained, k, chunk.out.response_cycle.data());
    if (cache_stage.records_shapes()) {
      chunk.out.edge_shapes.resize(k);
      for (size_t i = drained, j = 0; i < end; ++i, ++j) {
        chunk.out.edge_shapes[j] = cache_stage.shapes[i];
        cache_stage.shapes[i] = ProbeShapes{};  // the slot's next request starts from no shape
      }
    }
  }
  drained = end;
  if (sink != nullptr) {
    source.release(end);
    (*sink)(chunk);
  }
}

}  // namespace detail

void check_requests(const Frame& frame, const TraceRequest* requests, size_t n, size_t first) {
  const size_t nt = frame.regs.textures.size(), ns = frame.regs.samplers.size();
  std::vector<uint8_t> seen(nt * ns, 0);
  for (size_t j = 0; j < n; ++j) {
    const TraceRequest& r = requests[j];
    const size_t i = first + j;
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

namespace detail {

void derive_stats(const Frame& frame, const UnitConfig& ucfg, Unit& u, UnitOutput& out) {
  (void)ucfg;
  sim::Stats& st = out.stats;
  const RetireStats& rs = u.retire_stats;
  const size_t n = rs.requests;
  const size_t nt = frame.regs.textures.size();
  const size_t slots = stat_slots(nt);
  u.cache_stage.publish(st);
  u.address_gen.publish(st);
  add(st, UnitStat::Cycles, out.cycles);
  add(st, UnitStat::Pixels, n);
  add(st, UnitStat::MemoryBytes, u.mem.bytes_read());
  add(st, UnitStat::MemoryRequests, u.mem.requests());
  if (const dram::DramModel* d = u.mem.dram()) publish_dram_stats(st, *d);
  if (u.filter) {
    uint64_t busy = 0;
    for (const uint64_t b : u.filter->busy_cycles()) busy += b;
    add(st, UnitStat::FilterLaneBusyCycles, busy);
  }
  const auto directions = [&u](const std::vector<size_t>& of_slots) {
    std::vector<uint64_t> h(lee_jen::kDirections, 0);
    for (const size_t k : of_slots)
      for (size_t d = 0; d < h.size(); ++d) h[d] += u.edge_direction->chosen[k][d];
    return h;
  };
  if (u.edge_direction) {
    std::vector<size_t> all(slots);
    for (size_t k = 0; k < slots; ++k) all[k] = k;
    st.set_histogram(stat_key(UnitStat::EdgeDirection), directions(all));
  }
  st.set_histogram(stat_key(UnitStat::Latency), u.response.latency);
  // Per statistics slot (texture descriptor x material stage), from the requests' own cycles
  // (RetireStats): the requests, the output cycles given to them and their latencies.
  const std::vector<uint64_t>& slot_requests = rs.slot_requests;
  const std::vector<uint64_t>& slot_cycles = rs.slot_cycles;
  const std::vector<std::vector<uint64_t>>& slot_latency = rs.slot_latency;
  // The groups: per material stage and per texture descriptor, each the sum of its slots, with
  // every counter and histogram of the run, and the rates derived from them.
  const auto texture_label = [&frame](size_t t) { return fmt::format("{} {}", t, frame.textures[t].name); };
  for (size_t k = 0; k < slots; ++k) {
    if (slot_requests[k] == 0) continue;
    sim::Stats s;
    add(s, UnitStat::Pixels, slot_requests[k]);
    add(s, UnitStat::Cycles, slot_cycles[k]);
    u.cache_stage.publish_slot(s, k);
    u.address_gen.publish_slot(s, k);
    if (u.filter) add(s, UnitStat::FilterLaneBusyCycles, u.filter->busy_cycles()[k]);
    if (u.edge_direction) s.set_histogram(stat_key(UnitStat::EdgeDirection), directions({k}));
    s.set_histogram(stat_key(UnitStat::Latency), slot_latency[k]);
    st.group(kStageGroups, stage_group_label(static_cast<int>(k % kStatStages))).merge(s);
    st.group(kTextureGroups, texture_label(k / kStatStages)).merge(s);
  }
  derive_group_rates(st);
  // The tables: traffic per texture descriptor (requests and memory bytes counted apart from the
  // slots: the request tags, the cache's tag unit, the memory model) and per material stage.
  const std::vector<uint64_t>& tex_requests = rs.tex_requests;
  sim::Stats::Table textures{{"index", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t t = 0; t < nt; ++t) {
    const int ti = static_cast<int>(t);
    if (tex_requests[t] == 0 && u.cache.texture_hits(ti) + u.cache.texture_misses(ti) == 0) continue;
    textures.rows.emplace_back(texture_label(t),
                               std::vector<uint64_t>{t, tex_requests[t], u.cache.texture_hits(ti),
                                                     u.cache.texture_misses(ti), u.mem.texture_bytes(ti)});
  }
  st.set_table(stat_key(UnitStat::Textures), std::move(textures));
  if (u.cache_stage.any_compressed()) {
    sim::Stats::Table decoders{{"index", "decoded_blocks", "decoder_busy_cycles", "decoder_stall_cycles"}, {}};
    for (size_t t = 0; t < nt; ++t) {
      if (!frame.regs.textures[t].compressed || tex_requests[t] == 0) continue;
      uint64_t blocks = 0, busy = 0, stall = 0;
      for (size_t stage = 0; stage < kStatStages; ++stage) {
        const CacheStage::SlotCounters& c =
            u.cache_stage.slot_counters()[stat_slot(static_cast<int>(t), static_cast<int>(stage))];
        blocks += c.decoded_blocks;
        busy += c.decoder_busy;
        stall += c.decoder_stall;
      }
      decoders.rows.emplace_back(texture_label(t), std::vector<uint64_t>{t, blocks, busy, stall});
    }
    st.set_table(stat_key(UnitStat::Decoders), std::move(decoders));
  }
  sim::Stats::Table stages{{"stage", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t k = 0; k < kStatStages; ++k)
    if (const sim::Stats* g = st.find_group(kStageGroups, stage_group_label(static_cast<int>(k))))
      stages.rows.emplace_back(
          stage_group_label(static_cast<int>(k)),
          std::vector<uint64_t>{k, counter(*g, UnitStat::Pixels), counter(*g, UnitStat::CacheLineHits),
                                counter(*g, UnitStat::CacheLineMisses), counter(*g, UnitStat::MemoryBytes)});
  st.set_table(stat_key(UnitStat::Stages), std::move(stages));
  derive_rates(st, n, out.cycles);
}

}  // namespace detail

const char* unit_engine_name(UnitEngine e) { return kUnitEngineNames.name(e); }
UnitEngine unit_engine_from_name(const std::string& name) { return kUnitEngineNames.from_name(name); }

void publish_dram_stats(sim::Stats& st, const dram::DramModel& d) {
  const dram::Stats& ds = d.stats();
  add(st, UnitStat::DramBursts, ds.bursts);
  add(st, UnitStat::DramRowHits, ds.row_hits);
  add(st, UnitStat::DramRowEmpty, ds.row_empty);
  add(st, UnitStat::DramRowConflicts, ds.row_conflicts);
  add(st, UnitStat::DramActivates, ds.activates);
  add(st, UnitStat::DramRefreshes, ds.refreshes);
  std::vector<uint64_t> h = ds.latency_histogram;  // trailing empty buckets dropped
  while (!h.empty() && h.back() == 0) h.pop_back();
  st.set_histogram(stat_key(UnitStat::DramLatency), std::move(h));
}

void derive_group_rates(sim::Stats& st) {
  for (sim::Stats::Group& g : st.groups())
    derive_rates(g.stats, counter(g.stats, UnitStat::Pixels), counter(g.stats, UnitStat::Cycles));
}

void derive_rates(sim::Stats& st, size_t requests, uint64_t cycles) {
  const auto n = static_cast<double>(requests);
  set(st, UnitStat::PixelsPerClock, cycles ? n / static_cast<double>(cycles) : 0.0);
  set(st, UnitStat::MemoryBytesPerPixel, requests ? static_cast<double>(counter(st, UnitStat::MemoryBytes)) / n : 0.0);
  set(st, UnitStat::ProbesPerPixel, requests ? static_cast<double>(counter(st, UnitStat::Probes)) / n : 0.0);
  const uint64_t h = counter(st, UnitStat::CacheLineHits), m = counter(st, UnitStat::CacheLineMisses);
  set(st, UnitStat::CacheHitRate, h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0);
  const uint64_t sh = counter(st, UnitStat::CacheSectorHits), sl = counter(st, UnitStat::CacheSectorLookups);
  set(st, UnitStat::CacheSectorHitRate, sl ? static_cast<double>(sh) / static_cast<double>(sl) : 1.0);
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
  if (const uint64_t l2 = counter(st, UnitStat::L2Requests))
    set(st, UnitStat::L2HitRate, static_cast<double>(counter(st, UnitStat::L2Hits)) / static_cast<double>(l2));
  if (const uint64_t bursts = counter(st, UnitStat::DramBursts)) {
    set(st, UnitStat::DramRowHitRate, static_cast<double>(counter(st, UnitStat::DramRowHits)) / static_cast<double>(bursts));
    uint64_t reads = 0, sum = 0;
    if (const std::vector<uint64_t>* dl = st.histogram(stat_key(UnitStat::DramLatency)))
      for (size_t c = 0; c < dl->size(); ++c) {
        reads += (*dl)[c];
        sum += c * (*dl)[c];
      }
    set(st, UnitStat::DramLatencyMean, reads ? static_cast<double>(sum) / static_cast<double>(reads) : 0.0);
  }
}

}  // namespace tfu::rtl
