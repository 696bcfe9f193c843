#include "rtl/cost_model.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "rtl/dram.hpp"

namespace tfu::rtl {

namespace detail {
extern const char* const kFilterGatesJson;   // generated from rtl/sv/filter_gates.json (rtl/CMakeLists.txt)
// generated from rtl/sv/silicon_gates.json (rtl/CMakeLists.txt), in pieces to be joined
extern const char* const kSiliconGatesJsonPieces[];
extern const std::size_t kSiliconGatesJsonPieceCount;
}  // namespace detail

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
             ways = static_cast<uint64_t>(c.way_count());
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

namespace {

// What anisotropic filtering adds to a LOD unit and a filter (docs/design-space.md, "Cost"): the
// select of the major axis, the probe count, lambda with the log2(N^2) ROM, the probe generator.
// The squares of the two axes (aniso_axis_len2) are not counted: an isotropic LOD unit has them.
constexpr std::array kAnisoBlocks{"aniso_major_select", "aniso_count", "aniso_lambda", "aniso_probe"};
// What the footprint's true axes (SamplerDescriptor::aniso_axes Ellipse) add beside them in
// tfu_aniso_lod: the dot and cross products, the hypot (the major axis) and their probe count.
constexpr std::array kEllipseAxesBlocks{"aniso_dot_cross", "aniso_ellipse_major", "aniso_count_ellipse"};

// A frame's samplers as the cost model reads them: their modes, whether any filters
// anisotropically, and whether any of those on the footprint's true axes.
struct DatapathUse {
  std::vector<FilterMode> modes;
  bool anisotropic = false, ellipse_axes = false;
};
DatapathUse datapath_use(const std::vector<SamplerDescriptor>& samplers) {
  DatapathUse use;
  for (const SamplerDescriptor& d : samplers) {
    use.modes.push_back(d.mode);
    use.anisotropic = use.anisotropic || d.anisotropic();
    use.ellipse_axes = use.ellipse_axes || (d.anisotropic() && d.aniso_axes == AnisoAxes::Ellipse);
  }
  return use;
}

}  // namespace

const std::vector<GateBlock>& filter_gate_table() { return table().blocks; }
const std::string& filter_gate_source() { return table().source; }

FilterGates filter_datapath_gates(const std::vector<FilterMode>& modes, bool anisotropic, bool ellipse_axes) {
  std::vector<std::string> need;
  for (const FilterMode& m : modes) {
    need.emplace_back(block_of(m.base));
    if (m.mip == MipMode::Linear) need.emplace_back("level_blend");
  }
  if (anisotropic)
    for (const char* b : kAnisoBlocks) need.emplace_back(b);
  if (anisotropic && ellipse_axes)
    for (const char* b : kEllipseAxesBlocks) need.emplace_back(b);
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
  const DatapathUse use = datapath_use(samplers);
  return filter_datapath_gates(use.modes, use.anisotropic, use.ellipse_axes);
}

namespace {

// rtl/sv/silicon_gates.json's osu035 and osu018 rows (parsed once).
const std::vector<NodeBlock>& node_table(Node n) {
  static const std::array<std::vector<NodeBlock>, 2> t = [] {
    std::array<std::vector<NodeBlock>, 2> out;
    std::string text;
    for (std::size_t i = 0; i < detail::kSiliconGatesJsonPieceCount; ++i) text += detail::kSiliconGatesJsonPieces[i];
    const nlohmann::json j = nlohmann::json::parse(text);
    for (const Node node : {Node::Osu035, Node::Osu018})
      for (const auto& r : j.at(node_name(node))) {
        NodeBlock b;
        b.block = r.at("block").get<std::string>();
        b.area_um2 = r.at("area_um2").get<double>();
        b.fmax_mhz = r.at("fmax_reg2reg_mhz").get<double>();
        if (!r.at("fmax_in2reg_mhz").is_null())
          b.fmax_mhz = std::min(b.fmax_mhz, r.at("fmax_in2reg_mhz").get<double>());
        b.leakage_nw = r.at("leakage_nw").get<double>();
        b.flip_flops = r.at("flip_flops").get<int>();
        out[static_cast<size_t>(node)].push_back(std::move(b));
      }
    return out;
  }();
  return t[static_cast<size_t>(n)];
}

// From osu035_stdcells.lib / osu018_stdcells.lib (typical corner): DFFPOSX1 `area` and
// `cell_leakage_power`, NAND2X1 `area` and pin A `capacitance`, `nom_voltage`.
constexpr std::array<NodeTech, 2> kNodeTech{{
    {384, 0.112978, 96, 0.0177118, 3.3},  // osu035
    {96, 0.160725, 24, 0.0125, 1.8},      // osu018
}};

// The osu018 SRAM model: GlobalFoundries' GF180MCU single-port macro gf180mcu_fd_ip_sram__sram512x8m8wm1
// (github.com/google/globalfoundries-pdk-ip-gf180mcu_fd_ip_sram, its liberty file
// ..._tt_025C_1v80.lib: typical, 1.8 V, 25 C, the osu018 library's corner): `area` 209400.2768 um^2
// for 512 x 8 bits (its datasheet, ..._sram512x8m8wm1.rst: a 13.5 um^2 6T bit cell; the rest is the
// periphery, built of the process's 5 V transistors), CLK `internal_power` per edge (pF x V^2 = pJ)
// when reading (!CEN & GWEN) 103.176 and writing 112.563: an access is one rising and one falling edge.
constexpr double kGf180MacroAreaUm2 = 209400.2768, kGf180BitCellUm2 = 13.5;
constexpr int kGf180Words = 512, kGf180BitsPerWord = 8;
constexpr SramMacro kGf180Sram512x8{"gf180mcu_fd_ip_sram__sram512x8m8wm1",
                                    kGf180Words,
                                    kGf180BitsPerWord,
                                    kGf180MacroAreaUm2,
                                    2 * 103.176,
                                    2 * 112.563,
                                    "tt_025C_1v80",
                                    "GF180MCU SRAM macro gf180mcu_fd_ip_sram__sram512x8m8wm1, liberty tt_025C_1v80 "
                                    "(google/globalfoundries-pdk-ip-gf180mcu_fd_ip_sram)"};

// The osu035 SRAM model (no 0.35 um macro with published area and energy was found), the same
// 512 x 8 organisation from two published sources:
//   bit cells: OpenRAM's 6T cell of its scn4m_subm technology ("SCMOS 4m, 0.35um", lambda = 0.2 um,
//     the MOSIS SCMOS_SUBM rules the OSU 0.35 um cells are drawn in), technology/scn4m_subm/mag_lib/
//     cell_1rw.mag (github.com/VLSIDA/OpenRAM): abutment box 34 x 52 lambda = 6.8 x 10.4 um = 70.72 um^2;
//   periphery: the GF180 macro's, unscaled (209400.2768 - 4096 x 13.5 = 154104.2768 um^2): its
//     decoders, sense amplifiers and drivers are built of 5 V transistors, not smaller than 0.35 um ones;
//   energy per access: the GF180 macro's at 3.3 V, osu035's supply (liberty ..._tt_025C_3v30.lib:
//     CLK internal_power per edge reading 369.6, writing 408.606), unscaled for the same reason.
// Area per bit 108.34 um^2 (OpenRAM's cell x 4096 + the periphery, over 4096 bits); an estimate
// resting on the stated transfer of the periphery, not a characterised 0.35 um macro.
constexpr double kOpenRamScn4mBitCellUm2 = (34 * 0.2) * (52 * 0.2);
constexpr SramMacro kOsu035Sram512x8{
    "OpenRAM scn4m_subm 6T cells + gf180mcu_fd_ip_sram__sram512x8m8wm1 periphery",
    kGf180Words,
    kGf180BitsPerWord,
    kGf180Words * kGf180BitsPerWord * kOpenRamScn4mBitCellUm2 +
        (kGf180MacroAreaUm2 - kGf180Words * kGf180BitsPerWord * kGf180BitCellUm2),
    2 * 369.6,
    2 * 408.606,
    "tt_025C_3v30",
    "OpenRAM scn4m_subm cell_1rw.mag (VLSIDA/OpenRAM) bit cells; GF180MCU macro gf180mcu_fd_ip_sram__sram512x8m8wm1 "
    "periphery and liberty tt_025C_3v30 (google/globalfoundries-pdk-ip-gf180mcu_fd_ip_sram)"};

// DRAM power sheets: DRAMPower's memory specifications (github.com/tukl-msd/DRAMPower, memspecs/),
// whose currents are those of the Micron data sheets they are named after.
const std::vector<DramPowerSheet> kDramPowerSheets = {
    // ddr4-2400-x64: eight x8 devices; MICRON_4Gb_DDR4-2400_8bit_A.json: VDD 1.2 V, IDD0 60.75,
    // IDD2N 38.25, IDD3N 44.0, IDD4R 184.5 mA; 1200 MHz, BL8, tRC 55, tRAS 39 clocks.
    {"ddr4-2400-x64", 8, {{{1.2, 60.75, 38.25, 44.0, 184.5}, {0, 0, 0, 0, 0}}}, 1200, 8, 55, 39,
     "DRAMPower memspecs/MICRON_4Gb_DDR4-2400_8bit_A.json (Micron 4Gb DDR4 x8, DDR4-2400)"},
    // lpddr4-3200-x16: one x16 channel; MICRON_6Gb_LPDDR4-3200_32bit_A.json (a 6 Gb part: the 4 Gb
    // preset's own currents are not in the memspecs): VDD1 1.8 V: IDD0 3.5, IDD2N 2.0, IDD3N 2.25,
    // IDD4R 2.25 mA; VDD2 1.1 V: IDD02 45, IDD2N2 27, IDD3N2 30, IDD4R2 275 mA; 1600 MHz, BL16,
    // tRC 97, tRAS 68 clocks.
    {"lpddr4-3200-x16", 1, {{{1.8, 3.5, 2.0, 2.25, 2.25}, {1.1, 45.0, 27.0, 30.0, 275.0}}}, 1600, 16, 97, 68,
     "DRAMPower memspecs/MICRON_6Gb_LPDDR4-3200_32bit_A.json (Micron 6Gb LPDDR4, LPDDR4-3200; VDD1 and VDD2)"},
};

uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

}  // namespace

Node node_from_name(const std::string& name) {
  if (name == "osu035") return Node::Osu035;
  if (name == "osu018") return Node::Osu018;
  throw InputError(fmt::format("unknown node '{}' (expected {})", quote_input(name, 40), kNodeNames));
}

const char* node_name(Node n) { return n == Node::Osu035 ? "osu035" : "osu018"; }

const NodeBlock& node_block(Node n, const std::string& block) {
  for (const NodeBlock& b : node_table(n))
    if (b.block == block) return b;
  throw std::logic_error(fmt::format("rtl/sv/silicon_gates.json has no {} block '{}'", node_name(n), block));
}

const NodeTech& node_tech(Node n) { return kNodeTech[static_cast<size_t>(n)]; }

const SramMacro* sram_macro(Node n) { return n == Node::Osu018 ? &kGf180Sram512x8 : &kOsu035Sram512x8; }

const std::vector<DramPowerSheet>& dram_power_sheets() { return kDramPowerSheets; }

std::optional<DramCommandEnergy> dram_command_energy(int dram_part) {
  const dram::Part& part = dram::parts().at(static_cast<size_t>(dram_part - 1));
  for (const DramPowerSheet& s : kDramPowerSheets) {
    if (part.name != s.part) continue;
    const double ns_per_clock = 1000.0 / s.clock_mhz;
    const double t_burst = s.burst_length / 2 * ns_per_clock, t_rc = s.tRC_ck * ns_per_clock,
                 t_ras = s.tRAS_ck * ns_per_clock;
    DramCommandEnergy e;
    for (const DramSupply& v : s.supplies) {
      e.read_burst_pj += (v.idd4r_ma - v.idd3n_ma) * v.volts * t_burst;
      e.activate_pj += (v.idd0_ma * t_rc - v.idd3n_ma * t_ras - v.idd2n_ma * (t_rc - t_ras)) * v.volts;
    }
    e.read_burst_pj *= s.devices;
    e.activate_pj *= s.devices;
    e.burst_bytes = part.g.burst_bytes;
    return e;
  }
  return std::nullopt;
}

std::vector<std::pair<std::string, double>> datapath_instances(const std::vector<FilterMode>& modes, bool anisotropic,
                                                               int lanes, bool ellipse_axes) {
  const FilterGates g = filter_datapath_gates(modes, anisotropic, ellipse_axes);
  std::vector<std::pair<std::string, double>> out;
  for (const std::string& b : g.blocks) {
    double count = lanes;                          // one datapath per lane
    if (b == "cubic_filter") count = lanes / 4.0;  // the block is the 4-lane configuration
    if (b.rfind("aniso_", 0) == 0) count = 1;      // one anisotropic LOD unit and probe generator
    out.emplace_back(b, count);
  }
  return out;
}

SramAccessWords sram_access_words(const TexelCacheConfig& cache, const SramMacro& m) {
  const CacheSramBits bits = texel_cache_sram_bits(cache);
  const auto w = static_cast<uint64_t>(m.bits_per_word), ways = static_cast<uint64_t>(cache.way_count());
  const uint64_t set_lru = bits.lru / static_cast<uint64_t>(cache.sets()),
                 line = static_cast<uint64_t>(cache.line_bytes) * 8,
                 tag_valid = static_cast<uint64_t>(bits.tag_bits) + 1;
  SramAccessWords a;
  a.lookup_reads = ceil_div(ways * tag_valid + set_lru, w) + ceil_div(line, w);
  a.lookup_writes = ceil_div(set_lru, w);
  a.fill_writes = ceil_div(line, w) + ceil_div(tag_valid, w);
  return a;
}

uint64_t line_buffer_sram_bits(const UnitConfig& c) {
  return static_cast<uint64_t>(c.line_buffer_depth) * static_cast<uint64_t>(c.cache.line_bytes) * 8;
}

UnitCost unit_cost(Node n, const UnitConfig& config, const std::vector<SamplerDescriptor>& samplers, int units,
                   const RunCounts& run) {
  const DatapathUse use = datapath_use(samplers);
  const NodeTech& tech = node_tech(n);
  const double u = units;
  UnitCost c;
  c.instances = datapath_instances(use.modes, use.anisotropic, config.filter_lanes, use.ellipse_axes);
  c.fmax_mhz = std::numeric_limits<double>::infinity();
  for (const auto& [block, count] : c.instances) {
    const NodeBlock& b = node_block(n, block);
    c.datapath_um2 += u * count * b.area_um2;
    c.logic_leakage_nw += u * count * b.leakage_nw;
    c.fmax_mhz = std::min(c.fmax_mhz, b.fmax_mhz);
  }
  const double fifo_bits = u * config.miss_fifo_depth * kMissFifoEntryBits;
  c.miss_fifo_um2 = fifo_bits * tech.dff_area_um2;
  c.logic_leakage_nw += fifo_bits * tech.dff_leakage_nw;
  c.logic_um2 = c.datapath_um2 + c.miss_fifo_um2;
  // Per clock at fmax: leakage (nW / MHz = 1e-3 pJ) and the uniform-activity switching estimate.
  const double leakage_pj = c.logic_leakage_nw / c.fmax_mhz * 1e-3;
  const double switching_pj =
      kUniformActivity * (c.logic_um2 / tech.nand2_area_um2) * tech.nand2_a_pf * tech.vdd * tech.vdd;
  c.logic_pj = static_cast<double>(run.cycles) * (leakage_pj + switching_pj);
  if (const SramMacro* m = sram_macro(n)) {
    const CacheSramBits bits = texel_cache_sram_bits(config.cache);
    c.sram_um2 = u * static_cast<double>(bits.total() + line_buffer_sram_bits(config)) * m->area_um2 /
                 (m->words * m->bits_per_word);
    c.area_mm2 = (c.logic_um2 + *c.sram_um2) * 1e-6;
    const SramAccessWords a = sram_access_words(config.cache, *m);
    c.sram_pj = static_cast<double>(run.line_lookups) * (static_cast<double>(a.lookup_reads) * m->read_pj +
                                                         static_cast<double>(a.lookup_writes) * m->write_pj) +
                static_cast<double>(run.line_misses) * static_cast<double>(a.fill_writes) * m->write_pj;
    const double line_words = static_cast<double>(ceil_div(static_cast<uint64_t>(config.cache.line_bytes) * 8,
                                                           static_cast<uint64_t>(m->bits_per_word)));
    *c.sram_pj += static_cast<double>(run.line_misses) * line_words * (m->write_pj + m->read_pj);  // the line buffer
    const std::optional<DramCommandEnergy> d =
        config.memory.dram > 0 ? dram_command_energy(config.memory.dram) : std::nullopt;
    if (d)
      c.dram_pj = static_cast<double>(run.dram_bursts) * d->read_burst_pj +
                  static_cast<double>(run.dram_activates) * d->activate_pj;
    if (run.pixels && (config.memory.dram == 0 || d))
      c.energy_pj_per_pixel = (c.logic_pj + *c.sram_pj + c.dram_pj.value_or(0.0)) / static_cast<double>(run.pixels);
  }
  return c;
}

}  // namespace tfu::rtl
