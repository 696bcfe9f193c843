// dram: the DRAM behind the texel caches, read only: channels x ranks x bank groups x banks x rows,
// open-page or close-page, the JEDEC timing rules a read stream meets, refresh, and the address
// mapping (docs/memory-system.md).
//
// Time is counted in the DRAM's command clock (nCK, period tCK); the unit's clock is converted at
// the port with integer MHz on both sides (to_dram_cycle / to_unit_cycle round up: a request seen
// in the middle of a DRAM clock is taken at the next edge, data that arrives in the middle of a unit
// clock is used at the next one). No floating point in the timing; statistics print in ns.
//
// The controller (DramModel) serves reads first come, first served per channel, one burst at a
// time, in the order the caller issues them: the caller (a unit's miss port, or the L2 and its
// arbiter) fixes the order, so the result is deterministic. Each burst takes the commands its
// bank needs (PRE, ACT, RD) at the earliest cycle every rule allows; a rule is one function below,
// each with its own test (testbench/test_dram.cpp). What the model leaves out is listed in
// docs/memory-system.md ("What the DRAM model leaves out"): writes (and so tWR, tWTR, the bus
// turnaround), reordering schedulers (FR-FCFS), the rank-to-rank switch, per-bank refresh, power-down,
// the command/address bus beyond one command per clock per channel.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tfu::rtl::dram {

// ---- One part: the datasheet's figures, and the clocks they come to ----

// A datasheet minimum: "greater of nck clocks or ps picoseconds". In clocks (nCK) it is
// max(nck, ceil(ps / tCK)), the JEDEC rounding; tREFI, an average interval the controller must not
// exceed, rounds down instead (Timing::of).
struct Figure {
  int64_t ps = 0;
  int nck = 0;
};

struct Datasheet {
  Figure tAA;     // READ to first data (CL = tAA / tCK)
  Figure tRCD;    // ACTIVATE to READ, same bank
  Figure tRP;     // PRECHARGE to ACTIVATE, same bank
  Figure tRAS;    // ACTIVATE to PRECHARGE, same bank
  Figure tRC;     // ACTIVATE to ACTIVATE, same bank
  Figure tRTP;    // READ to PRECHARGE, same bank
  Figure tCCD_S;  // READ to READ, different bank group (or any bank, for parts without bank groups)
  Figure tCCD_L;  // READ to READ, same bank group
  Figure tRRD_S;  // ACTIVATE to ACTIVATE, different bank group, same rank
  Figure tRRD_L;  // ACTIVATE to ACTIVATE, same bank group, same rank
  Figure tFAW;    // at most four ACTIVATEs per rank in any tFAW window
  Figure tREFI;   // average interval between all-bank REFRESH commands of a rank
  Figure tRFC;    // REFRESH to ACTIVATE
  int burst_length;  // beats per burst (data on both clock edges: burst_length / 2 clocks)
};

// The same figures in command clocks, as the rules use them.
struct Timing {
  int CL, tRCD, tRP, tRAS, tRC, tRTP, tCCD_S, tCCD_L, tRRD_S, tRRD_L, tFAW, tREFI, tRFC;
  int burst;  // clocks one burst holds the data bus
  static Timing of(const Datasheet& d, int clock_mhz);
};

struct Geometry {
  int channels;
  int ranks;            // per channel
  int bank_groups;      // per rank (1: no bank groups)
  int banks_per_group;
  int rows;             // per bank
  int row_bytes;        // one row across the rank's devices (page size x devices)
  int burst_bytes;      // bytes one burst moves on the channel's data bus (bus bytes x burst length)
  int banks() const { return bank_groups * banks_per_group; }
  int columns() const { return row_bytes / burst_bytes; }  // bursts per row
};

struct Part {
  std::string_view name;
  int clock_mhz;  // command clock (1 / tCK); data rate is twice this
  Datasheet sheet;
  Geometry g;
  std::string_view source;  // where every figure comes from
};

// The presets. docs/memory-system.md shows presets_markdown() (a test holds the two equal).
const std::vector<Part>& parts();
std::string presets_markdown();
// The part called `name`; throws InputError naming `key` and the nearest valid name.
const Part& part(std::string_view name, std::string_view key = "dram.part");

// ---- Address mapping ----

// Fields of a burst address above the byte offset within a burst, most significant first, e.g.
// "row:rank:bank:bank_group:column:channel" (the default: consecutive bursts go to consecutive
// channels, then along a row; rows of one bank are the farthest apart). Every field must appear
// once; every count must be a power of two.
enum class Field { row, rank, bank, bank_group, column, channel };
// The mappings a unit configuration names (memory.dram_mapping): bank groups above the column (a
// stream stays in one bank group: tCCD_L apart), below it (a stream alternates groups: tCCD_S), and
// the banks below the column too (consecutive bursts spread over every bank).
inline constexpr std::array<const char*, 3> kMappings = {"row:rank:bank:bank_group:column:channel",
                                                         "row:rank:bank:column:bank_group:channel",
                                                         "row:column:rank:bank:bank_group:channel"};
struct Location {
  int channel = 0, rank = 0, bank_group = 0, bank = 0, row = 0, column = 0;
  friend bool operator==(const Location&, const Location&) = default;
};
class AddressMap {
 public:
  AddressMap(const Geometry& g, std::string_view order);  // throws InputError naming dram.mapping
  Location locate(uint64_t address) const;
  const std::string& order() const { return order_; }

 private:
  std::string order_;
  std::array<Field, 6> fields_{};  // least significant first
  std::array<int, 6> bits_{};
  int offset_bits_ = 0;
};

// ---- State the rules read ----

inline constexpr int64_t kNever = -(int64_t{1} << 40);  // "long ago": every rule is met

struct BankState {
  int open_row = -1;          // -1: precharged
  int64_t last_act = kNever;  // cycle of the last ACTIVATE
  int64_t last_pre = kNever;  // cycle of the last PRECHARGE (explicit or automatic)
  int64_t last_rd = kNever;   // cycle of the last READ
};
struct RankState {
  std::vector<BankState> banks;
  std::array<int64_t, 4> act_window{kNever, kNever, kNever, kNever};  // last four ACTIVATEs, oldest first
  std::vector<int64_t> last_act_in_group, last_rd_in_group;
  int64_t last_act = kNever, last_rd = kNever;
  int64_t refresh_until = kNever;  // cycle from which the rank takes commands after a REFRESH
  int64_t next_refresh = 0;        // cycle of the next scheduled REFRESH
};
struct ChannelState {
  std::vector<RankState> ranks;
  int64_t last_command = kNever;  // one command per clock per channel
  int64_t data_free = kNever;     // first clock the data bus is free
};

// ---- The rules: the earliest cycle at or after `t` a command may issue ----

// PRECHARGE of `bank`: tRAS after its ACTIVATE, tRTP after its READ.
int64_t earliest_precharge(const Timing& tm, const BankState& bank, int64_t t);
// ACTIVATE of bank `b` of group `group`: tRP after its PRECHARGE, tRC after its last ACTIVATE,
// tRRD_S / tRRD_L after the rank's last ACTIVATE (another / the same bank group), tFAW after the
// fourth-last ACTIVATE of the rank, tRFC after a REFRESH.
int64_t earliest_activate(const Timing& tm, const RankState& rank, int group, const BankState& bank, int64_t t);
// READ: tRCD after the bank's ACTIVATE, tCCD_S / tCCD_L after the rank's last READ (another / the
// same bank group), and the data bus: its data (CL clocks later) must not overlap the previous burst.
int64_t earliest_read(const Timing& tm, const RankState& rank, int group, const BankState& bank,
                      const ChannelState& channel, int64_t t);
// REFRESH (all banks of a rank): at its scheduled time, once every open bank can be precharged and
// tRP has passed (the controller precharges them first); returns the REFRESH cycle.
int64_t earliest_refresh(const Timing& tm, const RankState& rank, int64_t t);

// ---- The controller ----

enum class PagePolicy { open, close };  // close: READ with auto-precharge

struct Config {
  std::string part = "ddr4-2400-x64";
  PagePolicy policy = PagePolicy::open;
  std::string mapping = "row:rank:bank:bank_group:column:channel";
  int unit_clock_mhz = 1000;  // the units' clock, for the conversion at the port
  bool refresh = true;
};

struct Stats {
  uint64_t reads = 0;          // read requests (lines)
  uint64_t bursts = 0;
  uint64_t bytes = 0;
  uint64_t row_hits = 0;       // burst to the open row
  uint64_t row_empty = 0;      // burst to a precharged bank (ACT, READ)
  uint64_t row_conflicts = 0;  // burst to a bank with another row open (PRE, ACT, READ): a bank conflict
  uint64_t activates = 0, precharges = 0, refreshes = 0;
  int64_t first_request = -1, last_data = -1;  // DRAM cycles
  uint64_t latency_sum = 0;                    // DRAM cycles, request to last data, per read
  uint64_t latency_max = 0;
  std::vector<uint64_t> latency_histogram;     // reads by latency in DRAM cycles (last bucket: more)
  double row_hit_rate() const { return bursts ? double(row_hits) / double(bursts) : 0.0; }
};

class DramModel {
 public:
  explicit DramModel(const Config& cfg);  // throws InputError naming the key at fault
  // Reads `bytes` from `address` (split into bursts); `unit_cycle` must not decrease from one call to
  // the next (the caller's order is the service order). Returns the unit cycle at which the last byte
  // has arrived.
  uint64_t read(uint64_t unit_cycle, uint64_t address, int bytes);

  const Part& part() const { return *part_; }
  const Timing& timing() const { return tm_; }
  const Stats& stats() const { return stats_; }
  int64_t to_dram_cycle(uint64_t unit_cycle) const;
  uint64_t to_unit_cycle(int64_t dram_cycle) const;
  double ns(double dram_cycles) const { return dram_cycles * 1000.0 / part_->clock_mhz; }
  // Achieved bandwidth from the first request to the last data, GB/s.
  double bandwidth_gbps() const;
  // The smallest latency (ns) at or below which `fraction` of the reads completed.
  double latency_percentile_ns(double fraction) const;

 private:
  int64_t burst(int64_t t, const Location& at);
  void refresh_until(ChannelState& ch, int64_t t);

  const Part* part_;
  Timing tm_;
  Config cfg_;
  AddressMap map_;
  std::vector<ChannelState> channels_;
  Stats stats_;
  int64_t last_request_ = 0;
};

}  // namespace tfu::rtl::dram
