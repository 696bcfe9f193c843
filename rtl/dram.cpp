#include "rtl/dram.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"

namespace tfu::rtl::dram {

namespace {

// max(nck, ceil(ps / tCK)) with tCK = 10^6 / clock_mhz ps, in integers.
int clocks(const Figure& f, int clock_mhz) {
  const int64_t from_ps = (f.ps * clock_mhz + 999'999) / 1'000'000;
  return static_cast<int>(std::max<int64_t>(f.nck, from_ps));
}

constexpr int64_t from_ns(double v) { return static_cast<int64_t>(v * 1000.0 + 0.5); }  // table entries only

}  // namespace

Timing Timing::of(const Datasheet& d, int clock_mhz) {
  Timing t{};
  t.CL = clocks(d.tAA, clock_mhz);
  t.tRCD = clocks(d.tRCD, clock_mhz);
  t.tRP = clocks(d.tRP, clock_mhz);
  t.tRAS = clocks(d.tRAS, clock_mhz);
  t.tRC = clocks(d.tRC, clock_mhz);
  t.tRTP = clocks(d.tRTP, clock_mhz);
  t.tCCD_S = clocks(d.tCCD_S, clock_mhz);
  t.tCCD_L = clocks(d.tCCD_L, clock_mhz);
  t.tRRD_S = clocks(d.tRRD_S, clock_mhz);
  t.tRRD_L = clocks(d.tRRD_L, clock_mhz);
  t.tFAW = clocks(d.tFAW, clock_mhz);
  t.tREFI = static_cast<int>(d.tREFI.ps * clock_mhz / 1'000'000);  // an interval not to exceed: down
  t.tRFC = clocks(d.tRFC, clock_mhz);
  t.burst = d.burst_length / 2;
  return t;
}

const std::vector<Part>& parts() {
  // Each figure as its source prints it (ns, and the clock minimum where "greater of" applies).
  static const std::vector<Part> p = {
      {"ddr4-2400-x64", 1200,
       Datasheet{.tAA = {from_ns(13.32), 0}, .tRCD = {from_ns(13.32), 0}, .tRP = {from_ns(13.32), 0}, .tRAS = {from_ns(32), 0},
                 .tRC = {from_ns(45.32), 0}, .tRTP = {from_ns(7.5), 4}, .tCCD_S = {0, 4}, .tCCD_L = {from_ns(5), 4},
                 .tRRD_S = {from_ns(3.3), 4}, .tRRD_L = {from_ns(4.9), 4}, .tFAW = {from_ns(21), 20}, .tREFI = {from_ns(7800), 0},
                 .tRFC = {from_ns(260), 0}, .burst_length = 8},
       Geometry{.channels = 1, .ranks = 1, .bank_groups = 4, .banks_per_group = 4, .rows = 32768,
                .row_bytes = 8 * 1024, .burst_bytes = 64},
       "Micron 4Gb DDR4 SDRAM data sheet (4gb_ddr4_dram.pdf rev. G): speed bin -083E DDR4-2400 16-16-16 "
       "(tAA, tRCD, tRP 13.32 ns; tRAS 32 ns; tRC = tRAS + tRP), AC timing (tRTP max(4CK, 7.5 ns); tCCD_S 4CK; "
       "tCCD_L max(4CK, 5 ns); tRRD_S, tRRD_L max(4CK, 3.3 / 4.9 ns) and tFAW max(20CK, 21 ns) for a 1 KB "
       "page; tRFC1 260 ns for 4 Gb; tREFI 7.8 us); one rank of eight x8 devices (1 KB page, 15 row bits, "
       "16 banks in 4 groups): an 8 KB row, a 64-byte BL8 burst on the 64-bit bus"},
      {"lpddr4-3200-x16", 1600,
       Datasheet{.tAA = {0, 28}, .tRCD = {from_ns(18), 4}, .tRP = {from_ns(18), 4}, .tRAS = {from_ns(42), 3},
                 .tRC = {from_ns(60), 0}, .tRTP = {from_ns(7.5), 8}, .tCCD_S = {0, 8}, .tCCD_L = {0, 8},
                 .tRRD_S = {from_ns(10), 4}, .tRRD_L = {from_ns(10), 4}, .tFAW = {from_ns(40), 0}, .tREFI = {from_ns(3904), 0},
                 .tRFC = {from_ns(180), 0}, .burst_length = 16},
       Geometry{.channels = 1, .ranks = 1, .bank_groups = 1, .banks_per_group = 8, .rows = 32768,
                .row_bytes = 2 * 1024, .burst_bytes = 32},
       "JEDEC JESD209-4 (LPDDR4) for 3200 MT/s and 4 Gb per channel, as tabulated by NXP's S32 Design "
       "Studio DDR tool (RL 28 without DBI, nRTP 12 from tRTP max(8CK, 7.5 ns), tRPpb 18 ns, tRAS 42 ns, "
       "tREFI 3.904 us, tRFCab 180 ns) and the standard's core timings (tRCD max(4CK, 18 ns), tRRD max(4CK, "
       "10 ns), tFAW 40 ns, tCCD 8CK for BL16; tRC = tRAS + tRPpb); one x16 channel, 8 banks, 2 KB page: "
       "a 32-byte BL16 burst"},
      // A graphics DRAM. GDDR3 registers commands on CK and moves data on both edges of RDQS, which
      // runs at CK: 2 data beats per CK (1400 MT/s at 700 MHz), as DDR4 and LPDDR4 (burst_length / 2
      // clocks a burst). The data sheet prints the row and column timing in clocks per speed bin. The
      // -14 bin (700 MHz) is taken: Tables 38 and 39 print it alike and its tRC = tRAS + tRP (the
      // -12 bin's tRC 32 is below its tRAS 21 + tRP 13). No four-activate window (tFAW 0: the rule
      // never binds) and no bank groups (one group; tCCD and tRRD are both the _S and the _L figure).
      // READ to PRECHARGE is not a table entry: BL/2 clocks, the GDDR3 READ-to-PRECHARGE diagram.
      {"gddr3-1400-x32", 700,
       Datasheet{.tAA = {0, 11}, .tRCD = {0, 11}, .tRP = {0, 12}, .tRAS = {0, 18}, .tRC = {0, 30}, .tRTP = {0, 2},
                 .tCCD_S = {0, 2}, .tCCD_L = {0, 2}, .tRRD_S = {0, 7}, .tRRD_L = {0, 7}, .tFAW = {0, 0},
                 .tREFI = {from_ns(3900), 0}, .tRFC = {from_ns(52.0), 0}, .burst_length = 4},
       Geometry{.channels = 1, .ranks = 1, .bank_groups = 1, .banks_per_group = 8, .rows = 4096,
                .row_bytes = 2 * 1024, .burst_bytes = 16},
       "Qimonda HYB18H512321AF 512-Mbit GDDR3 data sheet rev. 1.73 (2005-08), table 38 (AC timings, "
       "speed bin -14; table 39 prints the same figures for -14): fCK 700 MHz at CL 11 (fCK11 max), tRC 30, "
       "tRAS 18, tRRD 7, tRP 12, tRCDRD 11, tCCD 2 clocks, tREFI 3.9 us, tRFC 52.0 ns; no tFAW, no bank "
       "groups; tRTP = BL/2 = 2 clocks (not tabulated: the READ-to-PRECHARGE diagram of GDDR3 data sheets, "
       "e.g. Samsung K4J55323QG rev. 1.1 p. 31, PRECHARGE two clocks after a BL4 READ); one x32 device, "
       "8 banks and two 32-bit words per clock (section 1.2 of the data sheet of its next die revision, "
       "HYB18H512321BF rev. 1.1, 2007-09), BL4: a 16-byte burst; 4096 rows of 2 KB per bank "
       "(512 Mbit = 8 banks x 4096 x 2 KB; the address table was not in the public copies read)"},
  };
  return p;
}

const Part& part(std::string_view name, std::string_view key) {
  std::vector<std::string> names;
  for (const Part& p : parts()) {
    if (p.name == name) return p;
    names.emplace_back(p.name);
  }
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  throw InputError(fmt::format("{}: unknown DRAM part '{}' ({}expected one of {})", key, name, did_you_mean(name, names), list));
}

std::string presets_markdown() {
  std::string md =
      "| part | clock MHz | CL | tRCD | tRP | tRAS | tRC | tRTP | tCCD S/L | tRRD S/L | tFAW | tREFI | tRFC | burst clocks "
      "| channels x ranks x groups x banks | row bytes | burst bytes | GB/s peak |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|\n";
  for (const Part& p : parts()) {
    const Timing t = Timing::of(p.sheet, p.clock_mhz);
    const Geometry& g = p.g;
    // Peak: one burst of burst_bytes every `burst` clocks per channel, in MB/s (integers) then GB/s.
    const int64_t peak_mbs = int64_t{p.clock_mhz} * g.burst_bytes * g.channels / t.burst;
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {}/{} | {}/{} | {} | {} | {} | {} | {}x{}x{}x{} | {} | {} | {}.{} |\n",
                      p.name, p.clock_mhz, t.CL, t.tRCD, t.tRP, t.tRAS, t.tRC, t.tRTP, t.tCCD_S, t.tCCD_L, t.tRRD_S,
                      t.tRRD_L, t.tFAW, t.tREFI, t.tRFC, t.burst, g.channels, g.ranks, g.bank_groups, g.banks_per_group,
                      g.row_bytes, g.burst_bytes, peak_mbs / 1000, peak_mbs % 1000 / 100);
  }
  md += "\nSources:\n\n";
  for (const Part& p : parts()) md += fmt::format("- `{}`: {}.\n", p.name, p.source);
  return md;
}

// ---- Address mapping ----

namespace {

constexpr std::array<std::string_view, 6> kFieldNames = {"row", "rank", "bank", "bank_group", "column", "channel"};

int log2_exact(int v, std::string_view what) {
  int b = 0;
  while ((1 << b) < v) ++b;
  if (v < 1 || (1 << b) != v) throw InputError(fmt::format("dram: {} {} is not a power of two", what, v));
  return b;
}

}  // namespace

AddressMap::AddressMap(const Geometry& g, std::string_view order) : order_(order) {
  const std::array<int, 6> counts = {g.rows, g.ranks, g.banks_per_group, g.bank_groups, g.columns(), g.channels};
  std::array<bool, 6> seen{};
  std::vector<Field> msb_first;
  size_t pos = 0;
  while (pos <= order.size()) {
    const size_t end = std::min(order.find(':', pos), order.size());
    const std::string_view word = order.substr(pos, end - pos);
    const auto it = std::find(kFieldNames.begin(), kFieldNames.end(), word);
    if (it == kFieldNames.end()) {
      std::vector<std::string> names(kFieldNames.begin(), kFieldNames.end());
      throw InputError(fmt::format("dram.mapping '{}': unknown field '{}' ({}fields: row, rank, bank, bank_group, column, channel)",
                                   order, word, did_you_mean(word, names)));
    }
    const auto f = static_cast<size_t>(it - kFieldNames.begin());
    if (seen[f]) throw InputError(fmt::format("dram.mapping '{}': field '{}' appears twice", order, word));
    seen[f] = true;
    msb_first.push_back(static_cast<Field>(f));
    pos = end + 1;
  }
  if (msb_first.size() != 6)
    throw InputError(fmt::format("dram.mapping '{}': every field once: row, rank, bank, bank_group, column, channel", order));
  for (size_t i = 0; i < 6; ++i) {
    const Field f = msb_first[5 - i];
    fields_[i] = f;
    bits_[i] = log2_exact(counts[static_cast<size_t>(f)], kFieldNames[static_cast<size_t>(f)]);
  }
  offset_bits_ = log2_exact(g.burst_bytes, "burst_bytes");
}

Location AddressMap::locate(uint64_t address) const {
  Location at;
  uint64_t a = address >> offset_bits_;
  for (size_t i = 0; i < 6; ++i) {
    const int v = static_cast<int>(a & ((uint64_t{1} << bits_[i]) - 1));
    a >>= bits_[i];
    switch (fields_[i]) {
      case Field::row: at.row = v; break;
      case Field::rank: at.rank = v; break;
      case Field::bank: at.bank = v; break;
      case Field::bank_group: at.bank_group = v; break;
      case Field::column: at.column = v; break;
      case Field::channel: at.channel = v; break;
    }
  }
  // Addresses beyond the memory wrap onto it (the row field takes the low bits of what is left).
  return at;
}

// ---- The rules ----

int64_t earliest_precharge(const Timing& tm, const BankState& bank, int64_t t) {
  return std::max({t, bank.last_act + tm.tRAS, bank.last_rd + tm.tRTP});
}

int64_t earliest_activate(const Timing& tm, const RankState& rank, int group, const BankState& bank, int64_t t) {
  const auto g = static_cast<size_t>(group);
  return std::max({t, bank.last_pre + tm.tRP, bank.last_act + tm.tRC, rank.last_act + tm.tRRD_S,
                   rank.last_act_in_group[g] + tm.tRRD_L, rank.act_window[0] + tm.tFAW, rank.refresh_until});
}

int64_t earliest_read(const Timing& tm, const RankState& rank, int group, const BankState& bank,
                      const ChannelState& channel, int64_t t) {
  const auto g = static_cast<size_t>(group);
  return std::max({t, bank.last_act + tm.tRCD, rank.last_rd + tm.tCCD_S, rank.last_rd_in_group[g] + tm.tCCD_L,
                   channel.data_free - tm.CL});
}

int64_t earliest_refresh(const Timing& tm, const RankState& rank, int64_t t) {
  int64_t r = std::max(t, rank.next_refresh);
  for (const BankState& b : rank.banks)
    if (b.open_row >= 0) r = std::max(r, earliest_precharge(tm, b, t) + tm.tRP);  // PRE, then tRP
    else r = std::max(r, b.last_pre + tm.tRP);
  return std::max(r, rank.refresh_until);
}

// ---- The controller ----

DramModel::DramModel(const Config& cfg)
    : part_(&dram::part(cfg.part)), tm_(Timing::of(part_->sheet, part_->clock_mhz)), cfg_(cfg), map_(part_->g, cfg.mapping) {
  if (cfg.unit_clock_mhz < 1 || cfg.unit_clock_mhz > 100000)
    throw InputError(fmt::format("dram.unit_clock_mhz {} must be in 1..100000", cfg.unit_clock_mhz));
  const Geometry& g = part_->g;
  channels_.resize(static_cast<size_t>(g.channels));
  for (ChannelState& ch : channels_) {
    ch.ranks.resize(static_cast<size_t>(g.ranks));
    for (size_t r = 0; r < ch.ranks.size(); ++r) {
      RankState& rank = ch.ranks[r];
      rank.banks.resize(static_cast<size_t>(g.banks()));
      rank.last_act_in_group.assign(static_cast<size_t>(g.bank_groups), kNever);
      rank.last_rd_in_group.assign(static_cast<size_t>(g.bank_groups), kNever);
      // Ranks refresh staggered by tREFI / ranks, so that they are not all busy at once.
      rank.next_refresh = cfg.refresh ? tm_.tREFI / g.ranks * static_cast<int64_t>(r) + tm_.tREFI
                                      : std::numeric_limits<int64_t>::max();
    }
  }
  stats_.latency_histogram.assign(4096, 0);
}

int64_t DramModel::to_dram_cycle(uint64_t unit_cycle) const {
  const uint64_t num = unit_cycle * static_cast<uint64_t>(part_->clock_mhz);
  const auto den = static_cast<uint64_t>(cfg_.unit_clock_mhz);
  return static_cast<int64_t>((num + den - 1) / den);
}

uint64_t DramModel::to_unit_cycle(int64_t dram_cycle) const {
  const uint64_t num = static_cast<uint64_t>(dram_cycle) * static_cast<uint64_t>(cfg_.unit_clock_mhz);
  const auto den = static_cast<uint64_t>(part_->clock_mhz);
  return (num + den - 1) / den;
}

// Every REFRESH due before `t` on the channel's ranks: all banks precharged (a PRE per open bank),
// the rank then busy for tRFC.
void DramModel::refresh_until(ChannelState& ch, int64_t t) {
  for (RankState& rank : ch.ranks) {
    while (rank.next_refresh <= t) {
      const int64_t r = earliest_refresh(tm_, rank, rank.next_refresh);
      for (BankState& b : rank.banks) {
        if (b.open_row >= 0) {
          b.last_pre = earliest_precharge(tm_, b, rank.next_refresh);
          b.open_row = -1;
          ++stats_.precharges;
        }
      }
      rank.refresh_until = r + tm_.tRFC;
      ch.last_command = std::max(ch.last_command, r);
      rank.next_refresh += tm_.tREFI;
      ++stats_.refreshes;
    }
  }
}

// One burst arriving at DRAM cycle `t`; returns the cycle its last beat is on the bus.
int64_t DramModel::burst(int64_t t, const Location& at) {
  ChannelState& ch = channels_[static_cast<size_t>(at.channel)];
  refresh_until(ch, t);
  RankState& rank = ch.ranks[static_cast<size_t>(at.rank)];
  const int group = at.bank_group;
  const auto g = static_cast<size_t>(group);
  BankState& bank = rank.banks[static_cast<size_t>(group * part_->g.banks_per_group + at.bank)];
  int64_t next = std::max(t, ch.last_command + 1);
  if (bank.open_row == at.row) {
    ++stats_.row_hits;
  } else {
    if (bank.open_row >= 0) {  // PRE the other row
      ++stats_.row_conflicts;
      bank.last_pre = earliest_precharge(tm_, bank, next);
      ++stats_.precharges;
      ch.last_command = bank.last_pre;
      next = bank.last_pre + 1;
    } else {
      ++stats_.row_empty;
    }
    const int64_t act = earliest_activate(tm_, rank, group, bank, next);  // ACT
    bank.last_act = act;
    bank.open_row = at.row;
    rank.last_act = act;
    rank.last_act_in_group[g] = act;
    std::rotate(rank.act_window.begin(), rank.act_window.begin() + 1, rank.act_window.end());
    rank.act_window[3] = act;
    ++stats_.activates;
    ch.last_command = act;
    next = act + 1;
  }
  const int64_t rd = earliest_read(tm_, rank, group, bank, ch, next);  // READ
  bank.last_rd = rd;
  rank.last_rd = rd;
  rank.last_rd_in_group[g] = rd;
  ch.last_command = rd;
  ch.data_free = rd + tm_.CL + tm_.burst;
  if (cfg_.policy == PagePolicy::close) {  // READ with auto-precharge: the bank closes when it may
    bank.last_pre = earliest_precharge(tm_, bank, rd);
    bank.open_row = -1;
    ++stats_.precharges;
  }
  ++stats_.bursts;
  return ch.data_free;
}

uint64_t DramModel::read(uint64_t unit_cycle, uint64_t address, int bytes) {
  if (bytes < 1) throw InputError(fmt::format("dram: a read of {} bytes", bytes));
  int64_t t = std::max(to_dram_cycle(unit_cycle), last_request_);
  last_request_ = t;
  if (stats_.first_request < 0) stats_.first_request = t;
  const auto bb = static_cast<uint64_t>(part_->g.burst_bytes);
  const uint64_t first = address / bb, last = (address + static_cast<uint64_t>(bytes) - 1) / bb;
  int64_t done = t;
  for (uint64_t b = first; b <= last; ++b) done = std::max(done, burst(t, map_.locate(b * bb)));
  ++stats_.reads;
  stats_.bytes += (last - first + 1) * bb;
  stats_.last_data = std::max(stats_.last_data, done);
  const auto latency = static_cast<uint64_t>(done - t);
  stats_.latency_sum += latency;
  stats_.latency_max = std::max(stats_.latency_max, latency);
  ++stats_.latency_histogram[std::min<size_t>(latency, stats_.latency_histogram.size() - 1)];
  return to_unit_cycle(done);
}

double DramModel::bandwidth_gbps() const {
  if (stats_.first_request < 0 || stats_.last_data <= stats_.first_request) return 0.0;
  return static_cast<double>(stats_.bytes) / ns(static_cast<double>(stats_.last_data - stats_.first_request));
}

double DramModel::latency_percentile_ns(double fraction) const {
  const auto need = static_cast<uint64_t>(fraction * static_cast<double>(stats_.reads) + 0.999999);
  uint64_t seen = 0;
  for (size_t i = 0; i < stats_.latency_histogram.size(); ++i) {
    seen += stats_.latency_histogram[i];
    if (seen >= need && need > 0) return ns(static_cast<double>(i));
  }
  return ns(static_cast<double>(stats_.latency_max));
}

}  // namespace tfu::rtl::dram
