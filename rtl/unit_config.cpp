#include "rtl/latency_tolerance.hpp"
#include "rtl/unit_config.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/json_input.hpp"
#include "cmodel/json_keys.hpp"
#include "cmodel/json_output.hpp"

namespace tfu::rtl {

namespace {

// "ideal", then the DRAM parts' names (string literals: they live as long as the table).
std::vector<const char*> dram_part_names() {
  std::vector<const char*> names{"ideal"};
  for (const dram::Part& p : dram::parts()) names.push_back(p.name.data());
  return names;
}

// The depths a datapath's field allows: `own` (the model's blocks alone, when no SV top is that
// shallow) and every depth the SV tops offer.
template <size_t N>
std::vector<int64_t> depths(int own, const std::array<OfferedDepth, N>& offered) {
  std::vector<int64_t> v;
  if (own < offered.front().clocks) v.push_back(own);
  for (const OfferedDepth& d : offered) v.push_back(d.clocks);
  return v;
}

#define TFU_INT_FIELD(member) \
  [](const UnitConfig& c) { return c.member; }, [](UnitConfig& c, int v) { c.member = v; }

const std::vector<UnitField>& fields() {
  static const std::vector<UnitField> f = {
      {"cache.line_bytes", "--line-bytes", "bytes per cache line; a tiled texture stores one tile per line (4x4 RGBA8 or 8x8 L8 at 64)",
       64, 1024, {64, 256, 1024}, {}, TFU_INT_FIELD(cache.line_bytes)},
      {"cache.capacity_bytes", "--cache-bytes", "data capacity; a whole number of sets", 64, int64_t{1} << 30, {}, {},
       TFU_INT_FIELD(cache.capacity_bytes)},
      {"cache.ways", "--ways", "associativity (LRU); 0: fully associative (one set of every line, at most 4096)", 0, 1024, {}, {}, TFU_INT_FIELD(cache.ways)},
      {"cache.banks", "--banks", "banks", 1, 4, {1, 4}, {}, TFU_INT_FIELD(cache.banks)},
      {"cache.bank_mapping", "--bank-mapping",
       "texel-parity: one texel per bank per clock; block-parity: a bank reads a whole line per clock (docs/texel-cache.md)",
       0, 1, {}, {"texel-parity", "block-parity"},
       [](const UnitConfig& c) { return static_cast<int>(c.cache.bank_mapping); },
       [](UnitConfig& c, int v) { c.cache.bank_mapping = static_cast<BankMapping>(v); }},
      {"cache.holds", "--cache-holds",
       "what lines of compressed textures hold: compressed blocks (decoded after the cache, per footprint) or "
       "decoded texels (decoded on fill; a line a tile of line_bytes / 4 texels)",
       0, 1, {}, {"compressed", "decoded"},
       [](const UnitConfig& c) { return static_cast<int>(c.cache.holds); },
       [](UnitConfig& c, int v) { c.cache.holds = static_cast<CacheHolds>(v); }},
      {"decoder.texels_per_clock", "--decoder-texels", "texels a block decoder produces per clock", 1, 256, {}, {},
       TFU_INT_FIELD(decoder.texels_per_clock)},
      {"decoder.units", "--decoders", "block decoders per unit (they share the jobs: texels_per_clock x units per clock)",
       1, 64, {}, {}, TFU_INT_FIELD(decoder.units)},
      {"decoder.latency", "--decoder-latency", "clocks from a decode job's last busy clock to its texels out", 0, 1000, {}, {},
       TFU_INT_FIELD(decoder.latency)},
      {"memory.latency", "--latency", "cycles from request to data", 0, 1000000, {}, {},
       TFU_INT_FIELD(memory.latency)},
      {"memory.bytes_per_cycle", "--bandwidth", "memory interface bandwidth, bytes per cycle", 1, 65536, {}, {},
       TFU_INT_FIELD(memory.bytes_per_cycle)},
      {"memory.dram", "--dram",
       "what serves the misses: the ideal memory (memory.latency) or a DRAM part, each unit its own unless memory.shared (docs/memory-system.md)",
       0, static_cast<int64_t>(dram::parts().size()), {}, dram_part_names(), TFU_INT_FIELD(memory.dram)},
      {"memory.dram_policy", "--dram-policy", "DRAM page policy: rows stay open, or every read auto-precharges", 0, 1, {},
       {"open", "close"}, TFU_INT_FIELD(memory.dram_policy)},
      {"memory.dram_mapping", "--dram-mapping", "DRAM address mapping, fields most significant first (docs/memory-system.md)",
       0, static_cast<int64_t>(dram::kMappings.size()) - 1, {},
       std::vector<const char*>(dram::kMappings.begin(), dram::kMappings.end()), TFU_INT_FIELD(memory.dram_mapping)},
      {"memory.unit_clock_mhz", "--unit-clock-mhz", "the unit's clock in MHz, for the DRAM's timing (DRAM parts only)", 1,
       100000, {}, {}, TFU_INT_FIELD(memory.unit_clock_mhz)},
      {"memory.shared", "--memory-shared",
       "private: each unit its own memory (interface and DRAM); shared: one for all units of a scene, misses served in "
       "one order (docs/memory-system.md); an L2 implies shared",
       0, 1, {}, {"private", "shared"}, TFU_INT_FIELD(memory.shared)},
      {"l2.capacity_bytes", "--l2-bytes",
       "capacity of the L2 all units of a scene share, between their texel-cache misses and memory; 0: no L2; a whole "
       "number of sets (line_bytes x ways x banks)",
       0, int64_t{1} << 30, {}, {}, TFU_INT_FIELD(l2.capacity_bytes)},
      {"l2.line_bytes", "--l2-line-bytes", "bytes per L2 line (each L2 miss reads one line from memory)", 16, 4096,
       {16, 32, 64, 128, 256, 512, 1024, 2048, 4096}, {}, TFU_INT_FIELD(l2.line_bytes)},
      {"l2.ways", "--l2-ways", "L2 associativity", 1, 64, {}, {}, TFU_INT_FIELD(l2.ways)},
      {"l2.banks", "--l2-banks", "L2 banks (line address mod banks), one lookup per cycle each", 1, 64, {}, {},
       TFU_INT_FIELD(l2.banks)},
      {"l2.hit_latency", "--l2-hit-latency", "cycles from an L2 lookup to its data on a hit", 1, 10000, {}, {},
       TFU_INT_FIELD(l2.hit_latency)},
      {"l2.requests_per_cycle", "--l2-requests", "requests the L2 takes per cycle from all units together", 1, 256, {}, {},
       TFU_INT_FIELD(l2.requests_per_cycle)},
      {"l2.replacement", "--l2-replacement", "L2 replacement: least recently used, or first filled first out", 0, 1, {},
       {"lru", "fifo"}, TFU_INT_FIELD(l2.replacement)},
      {"channel_depth", "--channel-depth", "skid-buffer depth between blocks", 1, 64, {}, {},
       TFU_INT_FIELD(channel_depth)},
      {"miss_fifo_depth", "--miss-fifo-depth",
       "footprints queued behind outstanding misses (Igehy et al. 1998; the depth a latency needs: docs/memory-system.md)",
       1, 65536, {}, {}, TFU_INT_FIELD(miss_fifo_depth)},
      {"line_buffer_depth", "--line-buffer-depth",
       "line slots holding missed lines from request until their footprint leaves the miss FIFO (Igehy et al.'s reorder "
       "buffer); a footprint is looked up only with room for the most lines one can miss (the least value)",
       kMaxFootprintLines, 65536, {}, {}, TFU_INT_FIELD(line_buffer_depth)},
      {"filter_lanes", "--lanes", "bilinear-equivalent multiplier lanes of the filter", 1, 4, {1, 2, 4}, {},
       TFU_INT_FIELD(filter_lanes)},
      {"filter.edge_stages", "--edge-stages",
       "clocks of the edge-preserving interpolator from the texel cache's register to its result: 3 "
       "tfu_edge_interp_top (Lee & Jen), 8 tfu_edge_interp_top_l8 (101.2 MHz in OSU 0.35 um); docs/cycle-model.md, "
       "\"Datapath depth\"",
       kEdgeDepths.front().clocks, kEdgeDepths.back().clocks, depths(kEdgeBlockClocks, kEdgeDepths), {},
       TFU_INT_FIELD(filter.edge_stages)},
      {"filter.bilinear_stages", "--bilinear-stages",
       "clocks of the filter (NEAREST, LINEAR, CUBIC) counted as the bilinear top's latency, its input register the "
       "texel cache's: 2 the filter block alone, 3 tfu_bilinear_top, 4 tfu_bilinear_top_l4 (101.2 MHz in OSU 0.35 um)",
       kFilterBlockDepth, kBilinearDepths.back().clocks, depths(kFilterBlockDepth, kBilinearDepths), {},
       TFU_INT_FIELD(filter.bilinear_stages)},
  };
  return f;
}
#undef TFU_INT_FIELD

std::string valid_text(const UnitField& f) {
  if (!f.names.empty()) {
    std::string s;
    for (const char* n : f.names) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
  }
  if (!f.allowed.empty()) {
    std::string s;
    for (int64_t v : f.allowed) s += (s.empty() ? "" : ", ") + std::to_string(v);
    return s;
  }
  return fmt::format("{}..{}", f.lo, f.hi);
}

void check_value(const UnitField& f, int64_t v) {
  const bool ok = f.allowed.empty() ? (v >= f.lo && v <= f.hi)
                                    : std::find(f.allowed.begin(), f.allowed.end(), v) != f.allowed.end();
  if (!ok) throw InputError(fmt::format("{} must be {}", v, f.allowed.empty() ? "in " + valid_text(f) : "one of " + valid_text(f)));
}

}  // namespace

std::span<const UnitField> unit_config_fields() { return fields(); }

const UnitField* find_unit_field(const std::string& key) {
  for (const UnitField& f : fields())
    if (key == f.key) return &f;
  return nullptr;
}

std::string UnitField::value_text(const UnitConfig& c) const {
  const int v = get(c);
  return names.empty() ? std::to_string(v) : fmt::format("\"{}\"", names[static_cast<size_t>(v)]);
}

void UnitField::set_text(UnitConfig& c, const std::string& text) const {
  if (!names.empty()) {
    for (size_t i = 0; i < names.size(); ++i)
      if (text == names[i]) {
        set(c, static_cast<int>(i));
        return;
      }
    throw InputError(fmt::format("'{}' is not one of {}", quote_input(text), valid_text(*this)));
  }
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    throw InputError(fmt::format("'{}' is not an integer", quote_input(text)));
  check_value(*this, v);
  set(c, static_cast<int>(v));
}

void UnitConfig::validate() const {
  for (const UnitField& f : fields()) {
    try {
      check_value(f, f.get(*this));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", f.key, e.what()));
    }
  }
  cache.validate();
  memory.validate();
  l2.validate();
}

// Reads the fields of a JSON object (nested objects are the dotted key's groups) into `c`; every
// key of the object is checked before any value is read.
void read_object(const nlohmann::json& obj, const std::string& prefix, UnitConfig& c, const std::string& name) {
  if (!obj.is_object()) throw InputError(fmt::format("{}: {}expected a JSON object", name, prefix.empty() ? "" : prefix + ": "));
  const auto dotted = [&](const std::string& k) { return prefix.empty() ? k : prefix + "." + k; };
  const auto known = [&](const std::string& k, const nlohmann::json& v) {
    const std::string key = dotted(k);
    if (!v.is_object()) return find_unit_field(key) != nullptr;
    for (const UnitField& f : fields())
      if (std::string(f.key).rfind(key + ".", 0) == 0) return true;  // a group of dotted keys
    return false;
  };
  if (const auto k = first_unknown_key(obj, known))
    throw InputError(fmt::format("{}: {}", name, unknown_key_text(dotted(*k))));
  for (const auto& item : obj.items()) {
    const std::string key = dotted(item.key());
    const nlohmann::json& v = item.value();
    if (v.is_object()) {
      read_object(v, key, c, name);
      continue;
    }
    const UnitField* f = find_unit_field(key);
    try {
      if (!f->names.empty()) {
        if (!v.is_string()) throw InputError("must be a string");
        f->set_text(c, v.get<std::string>());
      } else {
        if (!v.is_number_integer()) throw InputError("must be an integer");
        if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))
          throw InputError(fmt::format("value {} is out of range", json_number_text(v)));
        f->set_text(c, std::to_string(v.get<int64_t>()));
      }
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: '{}' {}", name, key, e.what()));
    }
  }
}

UnitConfig unit_config_from_json(const std::string& text, const std::string& name) {
  // InputError "NAME: line L, column C: [at KEY: ]..." for malformed JSON and numbers out of range.
  const nlohmann::json j = parse_json_input(text, name);
  UnitConfig c;
  read_object(j, "", c, name);
  try {
    c.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", name, e.what()));
  }
  return c;
}

std::string unit_config_to_json(const UnitConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const UnitField& f : fields()) {
    nlohmann::json* at = &j;
    std::string key = f.key;
    for (size_t dot; (dot = key.find('.')) != std::string::npos; key = key.substr(dot + 1)) at = &(*at)[key.substr(0, dot)];
    (*at)[key] = nlohmann::json::parse(f.value_text(c));
  }
  return json_dump(j, 2);
}

LatencyTolerantDepths latency_tolerant_depths(const UnitConfig& c, uint64_t footprints, uint64_t cycles) {
  if (cycles == 0) throw InputError("latency_tolerant_depths: a zero-latency run of no cycles");
  const auto line_cycles = static_cast<uint64_t>((c.cache.line_bytes + c.memory.bytes_per_cycle - 1) / c.memory.bytes_per_cycle);
  const uint64_t w = static_cast<uint64_t>(c.memory.latency) + line_cycles + 2;
  const UnitField& fifo = *find_unit_field("miss_fifo_depth");
  const UnitField& lines = *find_unit_field("line_buffer_depth");
  const uint64_t fifo_depth = (footprints * w + cycles - 1) / cycles;  // w < 2^21: exact for up to 2^43 footprints
  const auto line_bytes = static_cast<uint64_t>(c.cache.line_bytes);
  const uint64_t in_flight = (w * static_cast<uint64_t>(c.memory.bytes_per_cycle) + line_bytes - 1) / line_bytes;
  return {static_cast<int>(std::clamp<uint64_t>(fifo_depth, static_cast<uint64_t>(fifo.lo), static_cast<uint64_t>(fifo.hi))),
          static_cast<int>(std::min<uint64_t>(in_flight + kMaxFootprintLines, static_cast<uint64_t>(lines.hi)))};
}

std::string unit_config_markdown() {
  const UnitConfig def;
  std::string md = "| field | flag | valid | default | meaning |\n|---|---|---|---:|---|\n";
  for (const UnitField& f : fields())
    md += fmt::format("| `{}` | `{}` | {} | {} | {} |\n", f.key, f.flag, valid_text(f), f.value_text(def), f.meaning);
  return md;
}

}  // namespace tfu::rtl
