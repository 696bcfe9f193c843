#include "rtl/kernel/kernel.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>

#include <fnmatch.h>

#include <nlohmann/json.hpp>

#include "cmodel/json_output.hpp"

namespace tfu::sim {

std::string Stats::json_text() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : counters_) j["counters"][k] = v;
  for (const auto& [k, v] : values_) j["values"][k] = v;
  for (const auto& [k, v] : histograms_) j["histograms"][k] = v;
  for (const auto& [k, t] : tables_) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& [label, values] : t.rows) {
      nlohmann::json row;
      row["name"] = label;
      for (size_t c = 0; c < t.columns.size() && c < values.size(); ++c) row[t.columns[c]] = values[c];
      rows.push_back(row);
    }
    j["tables"][k] = rows;
  }
  for (const Group& g : groups_) j["groups"][g.breakdown][g.label] = nlohmann::json::parse(g.stats.json_text());
  return json_dump(j, 2);
}

Stats& Stats::group(const std::string& breakdown, const std::string& label) {
  for (Group& g : groups_)
    if (g.breakdown == breakdown && g.label == label) return g.stats;
  groups_.push_back({breakdown, label, Stats{}});
  return groups_.back().stats;
}

const Stats* Stats::find_group(const std::string& breakdown, const std::string& label) const {
  for (const Group& g : groups_)
    if (g.breakdown == breakdown && g.label == label) return &g.stats;
  return nullptr;
}

void Stats::write_json(std::ostream& os) const { os << json_text() << '\n'; }

void Stats::merge(const Stats& from, bool add_counters) {
  for (const Group& g : from.groups_) group(g.breakdown, g.label).merge(g.stats, true);
  if (add_counters)
    for (const auto& [k, v] : from.counters_) counters_[k] += v;
  for (const auto& [k, h] : from.histograms_) {
    auto& into = histograms_[k];
    if (into.size() < h.size()) into.resize(h.size());
    for (size_t i = 0; i < h.size(); ++i) into[i] += h[i];
  }
  for (const auto& [k, t] : from.tables_) {
    Table& into = tables_[k];
    if (into.columns.empty()) into.columns = t.columns;
    for (const auto& [label, values] : t.rows) {
      auto it = std::find_if(into.rows.begin(), into.rows.end(), [&label = label](const auto& r) { return r.first == label; });
      if (it == into.rows.end()) {
        into.rows.emplace_back(label, values);
      } else {
        for (size_t c = 0; c < values.size() && c < it->second.size(); ++c) it->second[c] += values[c];
      }
    }
  }
}

Module::Module(Simulator& sim, std::string name) : sim_(sim), name_(std::move(name)) {
  sim_.add_module(this);
}

namespace {
// VCD identifier codes: printable ASCII 33..126, base 94.
std::string vcd_id(size_t n) {
  std::string s;
  do {
    s += static_cast<char>(33 + n % 94);
    n /= 94;
  } while (n);
  return s;
}
std::string binary(uint64_t v, int width) {
  std::string s(static_cast<size_t>(width), '0');
  for (int i = 0; i < width; ++i)
    if ((v >> i) & 1u) s[static_cast<size_t>(width - 1 - i)] = '1';
  return s;
}
}  // namespace

bool VcdWriter::selects(const std::string& pattern, const std::string& path) {
  return fnmatch(pattern.c_str(), path.c_str(), 0) == 0 || fnmatch((pattern + ".*").c_str(), path.c_str(), 0) == 0;
}

void VcdWriter::select(std::vector<std::string> patterns) {
  if (!signals_.empty() || header_done_) throw CheckFailed("VCD signal selection must come before the first signal");
  patterns_ = std::move(patterns);
  matched_.assign(patterns_.size(), 0);
}

std::vector<std::string> VcdWriter::unmatched_patterns() const {
  std::vector<std::string> out;
  for (size_t k = 0; k < patterns_.size(); ++k)
    if (!matched_[k]) out.push_back(patterns_[k]);
  return out;
}

void VcdWriter::add(const std::string& path, int width, std::function<uint64_t()> value) {
  if (header_done_) throw CheckFailed("VCD signals must be added before the first sample");
  if (width < 1 || width > 64) throw InputError(fmt::format("VCD signal {}: width {} outside 1..64", path, width));
  offered_.push_back(path);
  if (!patterns_.empty()) {
    bool selected = false;
    for (size_t k = 0; k < patterns_.size(); ++k)
      if (selects(patterns_[k], path)) {
        matched_[k] = 1;
        selected = true;
      }
    if (!selected) return;
  }
  signals_.push_back({path, width, std::move(value), vcd_id(signals_.size()), 0, false});
}

void VcdWriter::add_clock(const std::string& path) {
  if (header_done_) throw CheckFailed("VCD clock must be added before the first sample");
  clock_path_ = path;
}

void VcdWriter::set_window(uint64_t from, uint64_t to) {
  if (from > to) throw InputError(fmt::format("VCD window: from cycle {} is after to cycle {}", from, to));
  from_ = from;
  to_ = to;
}

void VcdWriter::header() {
  out_ << "$timescale " << timescale_ << " $end\n";
  if (!clock_path_.empty()) {  // the clock: a signal with the next id and no value function
    clock_id_ = vcd_id(signals_.size());
    signals_.push_back({clock_path_, 1, {}, clock_id_, 0, true});
  }
  // Scopes from the dotted paths, in order of first appearance (signals sorted by path).
  std::vector<size_t> order(signals_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return signals_[a].path < signals_[b].path; });
  std::vector<std::string> open;
  for (size_t i : order) {
    const Signal& s = signals_[i];
    std::vector<std::string> parts;
    size_t p = 0;
    for (size_t dot; (dot = s.path.find('.', p)) != std::string::npos; p = dot + 1) parts.push_back(s.path.substr(p, dot - p));
    const std::string leaf = s.path.substr(p);
    size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    while (open.size() > common) {
      out_ << "$upscope $end\n";
      open.pop_back();
    }
    for (size_t k = common; k < parts.size(); ++k) {
      out_ << "$scope module " << parts[k] << " $end\n";
      open.push_back(parts[k]);
    }
    out_ << "$var wire " << s.width << ' ' << s.id << ' ' << leaf << " $end\n";
  }
  while (!open.empty()) {
    out_ << "$upscope $end\n";
    open.pop_back();
  }
  out_ << "$enddefinitions $end\n";
  header_done_ = true;
}

void VcdWriter::sample(uint64_t cycle) {
  if (!header_done_) header();
  if (cycle < from_ || cycle > to_) return;
  const bool clocked = !clock_id_.empty();
  const uint64_t time = clocked ? 2 * cycle : cycle;
  bool stamped = false;
  if (clocked) {
    out_ << '#' << time << "\n1" << clock_id_ << '\n';
    stamped = true;
  }
  for (Signal& s : signals_) {
    if (!s.value) continue;  // the clock
    const uint64_t v = s.value();
    if (s.dumped && v == s.last) continue;
    if (!stamped) {
      out_ << '#' << time << '\n';
      stamped = true;
    }
    if (s.width == 1) {
      out_ << (v & 1u) << s.id << '\n';
    } else {
      out_ << 'b' << binary(v, s.width) << ' ' << s.id << '\n';
    }
    s.last = v;
    s.dumped = true;
  }
  if (clocked) out_ << '#' << time + 1 << "\n0" << clock_id_ << '\n';
}

void Simulator::reset() {
  for (Clocked* c : clocked_) c->reset();
  for (ChannelBase* c : channels_) c->reset();
  cycle_ = last_progress_ = 0;
}

void Simulator::after_edge(bool progressed) {
  if (vcd_) {
    vcd_->sample(cycle_);
  } else if (idle_skip_ && !progressed) {
    uint64_t wake = Module::kNever;
    for (const Module* m : modules_) wake = std::min(wake, m->wake_cycle(cycle_));
    if (wake != Module::kNever && wake > cycle_) {
      const uint64_t n = wake - cycle_;
      for (Module* m : modules_) m->skip_cycles(n);
      cycle_ = wake;
      skipped_ += n;
    }
  }
}

std::string Simulator::dump() const {
  std::string s = fmt::format("cycle {}, last progress at cycle {}:", cycle_, last_progress_);
  for (const Module* m : modules_) {
    const std::string st = m->state();
    if (!st.empty()) s += fmt::format(" [{}: {}]", m->name(), st);
  }
  return s;
}

void Simulator::stop(uint64_t start, uint64_t max_cycles) const {
  if (cycle_ - start >= max_cycles)
    throw DeadlockError(fmt::format("simulation exceeded its limit of {} cycles at cycle {}", max_cycles, cycle_), dump());
  throw DeadlockError(fmt::format("no block made progress for {} cycles (cycle {}, last progress at cycle {})",
                                  watchdog_, cycle_, last_progress_),
                      dump());
}

ProgressBar::ProgressBar(const std::function<uint64_t()>& done, uint64_t total)
    : done_(done), total_(total), t0_(std::chrono::steady_clock::now()), last_(t0_) {}

namespace {
std::atomic<bool> g_progress_bars{true};
}  // namespace

void set_progress_bars(bool on) { g_progress_bars = on; }

void ProgressBar::update(uint64_t cycle) {
  if (total_ == 0 || !done_ || !g_progress_bars) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - t0_ > std::chrono::seconds(2) && now - last_ > std::chrono::milliseconds(500)) {
    std::fprintf(stderr, "\r  simulating: %5.1f %% (cycle %llu)",
                 100.0 * static_cast<double>(done_()) / static_cast<double>(total_), static_cast<unsigned long long>(cycle));
    last_ = now;
    printed_ = true;
  }
}

void ProgressBar::finish(uint64_t cycle) const {
  if (printed_) std::fprintf(stderr, "\r  simulating: 100.0 %% (cycle %llu)\n", static_cast<unsigned long long>(cycle));
}

}  // namespace tfu::sim
