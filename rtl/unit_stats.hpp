// The unit's statistics as a field table: every counter, value, histogram and table a run of the
// unit (either engine, one unit or a scene's several) publishes, by one enum and one constexpr row
// each (key, kind, meaning). Blocks publish and the CLI and the sweeps read through these names, never
// through a string typed twice; docs/cycle-model.md "Statistics" shows the table
// (`tfu sim --stats-fields`, tested against it: Docs.CycleModelShowsTheStatFields), and
// UnitStats.EveryPublishedKeyIsInTheTable holds the table equal to what runs publish.
// A level scene adds the loader's counts (q3::level_count_fields, their own field table).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "cmodel/enum_names.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

namespace dram {
class DramModel;
}

enum class StatKind { Counter, Value, Histogram, Table };

enum class UnitStat {
  Cycles,
  Pixels,
  Units,
  CacheLineHits,
  CacheLineMisses,
  CacheLineHitsLevel,
  CacheLineMissesLevel,
  CacheSectorHits,
  CacheSectorLookups,
  MemoryBytes,
  MemoryRequests,
  CacheFootprints,
  StallCacheMiss,
  StallBankConflict,
  StallBackpressure,
  StallLineBuffer,
  ShapeCross,
  ShapeT,
  ShapeL,
  FilterLaneBusyCycles,
  Probes,
  PixelsPerClock,
  MemoryBytesPerPixel,
  ProbesPerPixel,
  CacheHitRate,
  CacheSectorHitRate,
  LatencyMean,
  LatencyMin,
  LatencyMax,
  Latency,
  EdgeDirection,
  AnisoProbes,
  Textures,
  Stages,
  DecodedBlocks,
  DecoderBusyCycles,
  DecoderStallCycles,
  Decoders,
  DramBursts,
  DramRowHits,
  DramRowEmpty,
  DramRowConflicts,
  DramActivates,
  DramRefreshes,
  DramLatency,
  DramRowHitRate,
  DramLatencyMean,
  MemorySharedBy,
  L2Requests,
  L2Hits,
  L2Misses,
  L2BankConflicts,
  L2QueueCycles,
  L2MemoryBytes,
  L2HitRate,
  L2Units,
};

inline constexpr EnumNames<StatKind, 4> kStatKindNames{"statistic kind",
                                                       {{{StatKind::Counter, "counter"},
                                                         {StatKind::Value, "value"},
                                                         {StatKind::Histogram, "histogram"},
                                                         {StatKind::Table, "table"}}}};

struct UnitStatField {
  UnitStat id;
  const char* key;  // a per-level key ends in "_level" and is published as key + N (the MIP level)
  StatKind kind;
  const char* meaning;
  // In the groups (every statistic per material stage and per texture descriptor, counted over
  // the group's requests: the JSON's "groups"): nullptr, not published there; "" published with
  // the same meaning; else what it means in a group.
  const char* in_group;
  constexpr bool per_level() const {
    return id == UnitStat::CacheLineHitsLevel || id == UnitStat::CacheLineMissesLevel;
  }
};

// Row i is UnitStat i (checked below), so a key is one array read.
inline constexpr std::array<UnitStatField, 56> kUnitStatFields{{
    {UnitStat::Cycles, "cycles", StatKind::Counter, "clock cycles of the run (of a scene: the slowest unit's)",
     "the output cycles given to the group's requests: each request's retirement cycle minus the previous request's "
     "(the first: its retirement cycle + 1), summed over units; one unit's groups add up to its cycles"},
    {UnitStat::Pixels, "pixels", StatKind::Counter,
     "requests: every pixel of every shaded 2x2 quad, helper pixels included, once per material stage", ""},
    {UnitStat::Units, "units", StatKind::Counter, "units of a scene run (a scene run only)", nullptr},
    {UnitStat::CacheLineHits, "cache_line_hits", StatKind::Counter, "texel-cache line hits (tag unit)", ""},
    {UnitStat::CacheLineMisses, "cache_line_misses", StatKind::Counter, "texel-cache line misses (tag unit)", ""},
    {UnitStat::CacheLineHitsLevel, "cache_line_hits_level", StatKind::Counter,
     "line hits on MIP level N (levels with any access)", ""},
    {UnitStat::CacheLineMissesLevel, "cache_line_misses_level", StatKind::Counter,
     "line misses on MIP level N (levels with any access)", ""},
    {UnitStat::CacheSectorHits, "cache_sector_hits", StatKind::Counter,
     "sector lookups whose line was a hit (tag unit)", ""},
    {UnitStat::CacheSectorLookups, "cache_sector_lookups", StatKind::Counter,
     "32-byte sectors looked up: per footprint, each distinct 32-byte sector of its lines that a used tap falls in "
     "(rtl/texel_cache.hpp)",
     ""},
    {UnitStat::MemoryBytes, "memory_bytes", StatKind::Counter, "bytes read from memory",
     "bytes read for the group's misses"},
    {UnitStat::MemoryRequests, "memory_requests", StatKind::Counter, "memory requests (one per missed line)", ""},
    {UnitStat::CacheFootprints, "cache_footprints", StatKind::Counter,
     "footprints the texel cache looked up (one tag lookup each; the rate the miss FIFO's depth follows)", ""},
    {UnitStat::StallCacheMiss, "stall_cache_miss", StatKind::Counter,
     "cycles the miss-FIFO head waits for memory (texel cache stage)",
     "counted for the footprint at the miss-FIFO head"},
    {UnitStat::StallBankConflict, "stall_bank_conflict", StatKind::Counter,
     "cycles the tag port is held by a footprint needing several bank cycles (input side)",
     "counted for the footprint waiting for the tag port"},
    {UnitStat::StallBackpressure, "stall_backpressure", StatKind::Counter,
     "cycles the texel cache stage waits for a full next block", "counted for the footprint at the miss-FIFO head"},
    {UnitStat::StallLineBuffer, "stall_line_buffer", StatKind::Counter,
     "cycles the tag stage waits for free line-buffer slots, the miss FIFO having room (present only when nonzero)",
     "counted for the footprint waiting at the tag stage"},
    {UnitStat::ShapeCross, "shape_cross", StatKind::Counter, "edge kernels read as the full cross (edge modes)", ""},
    {UnitStat::ShapeT, "shape_T", StatKind::Counter, "edge kernels read as a T shape (edge modes)", ""},
    {UnitStat::ShapeL, "shape_L", StatKind::Counter, "edge kernels read as an L shape (edge modes)", ""},
    {UnitStat::FilterLaneBusyCycles, "filter_lane_busy_cycles", StatKind::Counter,
     "lane-cycles the filter's lanes computed (filter modes)", ""},
    {UnitStat::Probes, "probes", StatKind::Counter, "probes (anisotropic samples; 1 per pixel otherwise)", ""},
    {UnitStat::PixelsPerClock, "pixels_per_clock", StatKind::Value, "pixels / cycles",
     "the group's pixels / its cycles"},
    {UnitStat::MemoryBytesPerPixel, "memory_bytes_per_pixel", StatKind::Value, "memory_bytes / pixels", ""},
    {UnitStat::ProbesPerPixel, "probes_per_pixel", StatKind::Value, "probes / pixels", ""},
    {UnitStat::CacheHitRate, "cache_hit_rate", StatKind::Value, "line hits / (hits + misses); 1 without accesses", ""},
    {UnitStat::CacheSectorHitRate, "cache_sector_hit_rate", StatKind::Value,
     "sector hits / sector lookups (as GPUs' l1tex__t_sector_hit_rate); 1 without accesses", ""},
    {UnitStat::LatencyMean, "latency_mean", StatKind::Value, "mean request latency in clocks", ""},
    {UnitStat::LatencyMin, "latency_min", StatKind::Value, "least request latency in clocks", ""},
    {UnitStat::LatencyMax, "latency_max", StatKind::Value, "greatest request latency in clocks", ""},
    {UnitStat::Latency, "latency", StatKind::Histogram, "requests per latency (bucket = clocks)", ""},
    {UnitStat::EdgeDirection, "edge_direction", StatKind::Histogram,
     "edge-preserving probes per chosen direction index (edge modes)", ""},
    {UnitStat::AnisoProbes, "aniso_probes", StatKind::Histogram, "pixels per probe count N (when a bound sampler is anisotropic)",
     ""},
    {UnitStat::Textures, "textures", StatKind::Table,
     "per texture descriptor: index, requests, line_hits, line_misses, memory_bytes", nullptr},
    {UnitStat::Stages, "stages", StatKind::Table,
     "per material stage: stage, requests, line_hits, line_misses, memory_bytes", nullptr},
    {UnitStat::DecodedBlocks, "decoded_blocks", StatKind::Counter,
     "compressed blocks decoded: each footprint's distinct blocks (cache.holds compressed) or each fill's (decoded; "
     "compressed textures only)",
     ""},
    {UnitStat::DecoderBusyCycles, "decoder_busy_cycles", StatKind::Counter,
     "clocks the block decoders decode (compressed textures only)", ""},
    {UnitStat::DecoderStallCycles, "decoder_stall_cycles", StatKind::Counter,
     "clocks decode jobs wait for busy decoders (compressed textures only)", ""},
    {UnitStat::Decoders, "decoders", StatKind::Table,
     "per compressed texture descriptor: index, decoded_blocks, decoder_busy_cycles, decoder_stall_cycles", nullptr},
    {UnitStat::DramBursts, "dram_bursts", StatKind::Counter, "DRAM bursts read (memory.dram a DRAM part only)", nullptr},
    {UnitStat::DramRowHits, "dram_row_hits", StatKind::Counter, "DRAM bursts to the open row", nullptr},
    {UnitStat::DramRowEmpty, "dram_row_empty", StatKind::Counter, "DRAM bursts to a precharged bank (ACTIVATE, READ)",
     nullptr},
    {UnitStat::DramRowConflicts, "dram_row_conflicts", StatKind::Counter,
     "DRAM bursts to a bank with another row open (PRECHARGE, ACTIVATE, READ): bank conflicts", nullptr},
    {UnitStat::DramActivates, "dram_activates", StatKind::Counter, "DRAM ACTIVATE commands", nullptr},
    {UnitStat::DramRefreshes, "dram_refreshes", StatKind::Counter, "DRAM REFRESH commands", nullptr},
    {UnitStat::DramLatency, "dram_latency", StatKind::Histogram,
     "DRAM reads per latency, request to last data (bucket = DRAM clocks; the last bucket: more)", nullptr},
    {UnitStat::DramRowHitRate, "dram_row_hit_rate", StatKind::Value, "dram_row_hits / dram_bursts", nullptr},
    {UnitStat::DramLatencyMean, "dram_latency_mean", StatKind::Value, "mean DRAM read latency in DRAM clocks", nullptr},
    {UnitStat::MemorySharedBy, "memory_shared_by", StatKind::Counter,
     "units whose misses go through one memory system (memory.shared or an L2; a scene run only): the DRAM counters "
     "are that memory's",
     nullptr},
    {UnitStat::L2Requests, "l2_requests", StatKind::Counter, "L2 line requests (an L1 miss: one per L2 line it covers; L2 only)",
     nullptr},
    {UnitStat::L2Hits, "l2_hits", StatKind::Counter, "L2 hits (a hit on a line still being filled included)", nullptr},
    {UnitStat::L2Misses, "l2_misses", StatKind::Counter, "L2 misses (each reads l2.line_bytes from memory)", nullptr},
    {UnitStat::L2BankConflicts, "l2_bank_conflicts", StatKind::Counter,
     "L2 requests whose bank was busy in the cycle they entered", nullptr},
    {UnitStat::L2QueueCycles, "l2_queue_cycles", StatKind::Counter,
     "cycles L2 requests waited from issue to lookup (input slots and banks), summed", nullptr},
    {UnitStat::L2MemoryBytes, "l2_memory_bytes", StatKind::Counter,
     "bytes the L2 read from memory: l2_misses x l2.line_bytes (memory_bytes: what the L1s read from the L2)", nullptr},
    {UnitStat::L2HitRate, "l2_hit_rate", StatKind::Value, "l2_hits / l2_requests", nullptr},
    {UnitStat::L2Units, "l2_units", StatKind::Table,
     "per unit: unit, l2_requests, l2_hits, l2_misses, l2_bank_conflicts, l2_queue_cycles", nullptr},
}};

constexpr bool unit_stat_rows_in_order() {
  for (size_t i = 0; i < kUnitStatFields.size(); ++i)
    if (static_cast<size_t>(kUnitStatFields[i].id) != i) return false;
  return true;
}
static_assert(unit_stat_rows_in_order(), "kUnitStatFields: row i must be UnitStat i");

constexpr const char* stat_key(UnitStat s) { return kUnitStatFields[static_cast<size_t>(s)].key; }
// A per-level key: "cache_line_hits_level3".
std::string stat_key(UnitStat s, int level);

// The groups' breakdowns and labels (sim::Stats::group): per material stage ("stage 1") and per
// texture descriptor ("3 NAME", as the tables' rows).
inline constexpr const char* kStageGroups = "stage";
inline constexpr const char* kTextureGroups = "texture";
std::string stage_group_label(int stage);

// Reads and writes by name (sim::Stats stays a generic name-keyed store).
inline uint64_t counter(const sim::Stats& st, UnitStat s) { return st.counter(stat_key(s)); }
inline double value(const sim::Stats& st, UnitStat s) { return st.value(stat_key(s)); }
inline void add(sim::Stats& st, UnitStat s, uint64_t n) { st.add(stat_key(s), n); }
inline void set(sim::Stats& st, UnitStat s, double v) { st.set(stat_key(s), v); }

// A DRAM's counters and latency histogram (a unit's own DRAM, or the one a scene's units share).
void publish_dram_stats(sim::Stats& st, const dram::DramModel& d);

// The table as Markdown (`tfu sim --stats-fields`; docs/cycle-model.md "Statistics").
std::string unit_stats_markdown();

}  // namespace tfu::rtl
