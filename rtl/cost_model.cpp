#include "rtl/cost_model.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"

namespace tfu::rtl {

namespace detail {
extern const char* const kFilterGatesJson;  // generated from rtl/sv/filter_gates.json (rtl/CMakeLists.txt)
}

namespace {

int ceil_log2(uint64_t v) { return v <= 1 ? 0 : static_cast<int>(std::bit_width(v - 1)); }

struct Table {
  std::vector<GateBlock> blocks;
  std::string source;
};

const Table& table() {
  static const Table t = [] {
    Table out;
    const nlohmann::json j = nlohmann::json::parse(detail::kFilterGatesJson);
    out.source = j.at("source").get<std::string>();
    for (const auto& b : j.at("blocks"))
      out.blocks.push_back({b.at("block").get<std::string>(), b.at("ge").get<double>(), b.at("flip_flops").get<int>()});
    return out;
  }();
  return t;
}

const char* block_of(BaseFilter b) {
  switch (b) {
    case BaseFilter::Nearest:
    case BaseFilter::Linear: return "bilinear_top";
    case BaseFilter::Cubic: return "cubic_filter";
    case BaseFilter::EdgePreserving: return "edge_interp_top";
  }
  return "bilinear_top";
}

}  // namespace

CacheSramBits texel_cache_sram_bits(const TexelCacheConfig& c) {
  c.validate();
  const auto lines = static_cast<uint64_t>(c.lines()), sets = static_cast<uint64_t>(c.sets()),
             ways = static_cast<uint64_t>(c.ways);
  const int offset_bits = ceil_log2(static_cast<uint64_t>(c.line_bytes));
  const uint64_t line_space = uint64_t{1} << (kAddressBits - offset_bits);  // distinct line addresses
  CacheSramBits b;
  b.tag_bits = ceil_log2((line_space + sets - 1) / sets);
  b.data = static_cast<uint64_t>(c.capacity_bytes) * 8;
  b.tag = lines * static_cast<uint64_t>(b.tag_bits);
  b.valid = lines;
  b.lru = sets * ways * static_cast<uint64_t>(ceil_log2(ways));
  return b;
}

const std::vector<GateBlock>& filter_gate_table() { return table().blocks; }
const std::string& filter_gate_source() { return table().source; }

FilterGates filter_datapath_gates(const std::vector<FilterMode>& modes, bool anisotropic) {
  std::vector<std::string> need;
  for (const FilterMode& m : modes) {
    need.emplace_back(block_of(m.base));
    if (m.mip == MipMode::Linear) need.emplace_back("level_blend");
  }
  if (anisotropic)
    for (const char* b : {"aniso_major_select", "aniso_count", "aniso_lambda", "aniso_probe"}) need.emplace_back(b);
  FilterGates g;
  for (const GateBlock& b : filter_gate_table())
    if (std::find(need.begin(), need.end(), b.block) != need.end()) {
      g.blocks.push_back(b.block);
      g.ge += b.ge;
    }
  for (const std::string& n : need)
    if (std::find(g.blocks.begin(), g.blocks.end(), n) == g.blocks.end())
      throw std::logic_error(fmt::format("rtl/sv/filter_gates.json has no block '{}'", n));
  return g;
}

FilterGates filter_datapath_gates(const std::vector<SamplerDescriptor>& samplers) {
  std::vector<FilterMode> modes;
  bool anisotropic = false;
  for (const SamplerDescriptor& d : samplers) {
    modes.push_back(d.mode);
    anisotropic = anisotropic || d.anisotropic();
  }
  return filter_datapath_gates(modes, anisotropic);
}

}  // namespace tfu::rtl
