// The unit's architectural parameters (the hardware, not its programming: descriptors are in
// cmodel/descriptors.hpp). One field table, unit_config_fields(), drives the struct's JSON reader
// and writer, the command-line overrides of `tfu sim` (and the sweep's dotted grid keys), and the
// table in docs/cycle-model.md (`tfu sim --config-fields`).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rtl/datapath_depth.hpp"
#include "rtl/l2_cache.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

// The filter datapaths' pipeline depths, in clocks: the latency of the SV top each stands for
// (rtl/datapath_depth.hpp; how the model reaches it: rtl/pipeline_registers.hpp).
struct FilterDepthConfig {
  int edge_stages = kEdgeBlockClocks;       // 3 (tfu_edge_interp_top) or 8 (tfu_edge_interp_top_l8)
  int bilinear_stages = kFilterBlockDepth;  // 2 (the filter block), 3 (tfu_bilinear_top) or 4 (tfu_bilinear_top_l4)
  friend bool operator==(const FilterDepthConfig&, const FilterDepthConfig&) = default;
};

struct UnitConfig {
  TexelCacheConfig cache{};
  MemoryConfig memory{};
  L2Config l2{};              // the L2 shared by a scene's units (off by default: rtl/l2_cache.hpp)
  int channel_depth = 2;      // skid buffers between blocks
  int miss_fifo_depth = 128;  // footprints queued in the texel cache behind outstanding misses
  int line_buffer_depth = 64;  // missed lines held from request until their footprint leaves the miss FIFO
  int filter_lanes = 1;       // bilinear-equivalent multiplier lanes of the filter (1, 2 or 4)
  DecoderConfig decoder{};    // block decoders of compressed textures (rtl/texel_cache.hpp)
  FilterDepthConfig filter{};  // the filter datapaths' pipeline depths
  // (Simulation options such as idle-cycle skipping are not architecture: ClockedOptions, tfu_unit.hpp.)
  void validate() const;  // every field's range, then the relations between fields; InputError naming the field
  friend bool operator==(const UnitConfig&, const UnitConfig&) = default;
};

// One field: its dotted JSON key, its command-line flag, what it means, and its valid values: an
// integer range [lo, hi], a set of integers, or names (stored as the index into `names`).
struct UnitField {
  const char* key;   // "cache.capacity_bytes"
  const char* flag;  // "--cache-bytes"
  const char* meaning;
  int64_t lo, hi;                   // integer range (names: 0 .. names.size() - 1)
  std::vector<int64_t> allowed;     // if not empty: the only valid integers
  std::vector<const char*> names;   // if not empty: a named choice
  int (*get)(const UnitConfig& c);
  void (*set)(UnitConfig& c, int value);
  std::string value_text(const UnitConfig& c) const;  // the value as JSON text
  // Parses `text` (an integer, or one of `names`) into the field; InputError without the key.
  void set_text(UnitConfig& c, const std::string& text) const;
};
std::span<const UnitField> unit_config_fields();
const UnitField* find_unit_field(const std::string& key);  // nullptr if unknown

// Parses a config JSON object; unknown keys and bad values are InputErrors naming file and key.
UnitConfig unit_config_from_json(const std::string& text, const std::string& name);
std::string unit_config_to_json(const UnitConfig& c);
// The field table as Markdown (key, flag, valid values, default, meaning).
std::string unit_config_markdown();

}  // namespace tfu::rtl
