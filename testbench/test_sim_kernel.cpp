// Simulation kernel: two-phase registers, valid/ready channels with skid buffers, order
// independence, back-pressure, deadlock watchdog, VCD and statistics output.
#include <sstream>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "rtl/kernel/kernel.hpp"

namespace tfu::sim {
namespace {

// Source -> ch_a -> Doubler -> ch_b -> Sink, the sink accepting on a given duty pattern.
struct Source : Module {
  Channel<int>& out;
  int next = 0, count;
  Source(Simulator& s, Channel<int>& o, int n) : Module(s, "source"), out(o), count(n) {}
  void evaluate() override {
    if (next < count && out.can_push()) {
      out.push(next++);
      sim_.progress();
    }
  }
};
struct Doubler : Module {
  Channel<int>& in;
  Channel<int>& out;
  Doubler(Simulator& s, Channel<int>& i, Channel<int>& o) : Module(s, "doubler"), in(i), out(o) {}
  void evaluate() override {
    if (in.can_pop() && out.can_push()) {
      out.push(2 * in.front());
      in.pop();
      sim_.progress();
    }
  }
  std::string state() const override { return in.state() + ", " + out.state(); }
};
struct Sink : Module {
  Channel<int>& in;
  std::vector<std::pair<uint64_t, int>> got;  // (cycle, value)
  int period;                                 // accepts when cycle % period == 0 (0: never)
  Sink(Simulator& s, Channel<int>& i, int p) : Module(s, "sink"), in(i), period(p) {}
  void evaluate() override {
    if (period != 0 && sim_.cycle() % static_cast<uint64_t>(period) == 0 && in.can_pop()) {
      got.emplace_back(sim_.cycle(), in.front());
      in.pop();
      sim_.progress();
    }
  }
};

struct Pipe {
  Simulator sim{50};
  Channel<int> a{"a", 2}, b{"b", 2};
  Source src;
  Doubler dbl;
  Sink snk;
  Pipe(int n, int period) : src(sim, a, n), dbl(sim, a, b), snk(sim, b, period) {
    sim.add_clocked(&a);
    sim.add_clocked(&b);
  }
  void run(int n) { sim.run([&] { return static_cast<int>(snk.got.size()) == n; }, 100000); }
};

TEST(SimKernel, OneTransferPerCycleThroughSkidBuffers) {
  Pipe p(100, 1);
  p.run(100);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(p.snk.got[static_cast<size_t>(i)].second, 2 * i);
  // Two registered hops: the first result appears in cycle 2, then one per cycle.
  EXPECT_EQ(p.snk.got.front().first, 2u);
  EXPECT_EQ(p.snk.got.back().first, 101u);
}

TEST(SimKernel, EvaluationOrderDoesNotMatter) {
  Pipe fwd(60, 3), rev(60, 3);
  rev.sim.set_order(Simulator::Order::Reverse);
  fwd.run(60);
  rev.run(60);
  EXPECT_EQ(fwd.snk.got, rev.snk.got);
}

TEST(SimKernel, BackPressureKeepsOrderAndRate) {
  Pipe p(50, 2);
  p.run(50);
  for (size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(p.snk.got[i].second, 2 * static_cast<int>(i));
    if (i > 0) {
      EXPECT_EQ(p.snk.got[i].first - p.snk.got[i - 1].first, 2u);
    }
  }
}

TEST(SimKernel, WatchdogStopsADeadlockWithAStateDump) {
  Pipe p(10, 0);  // the sink never accepts
  try {
    p.run(10);
    FAIL() << "no deadlock reported";
  } catch (const DeadlockError& e) {
    // One summary line; the per-stage state is in dump() (the CLI writes it to a file, exit 4).
    const std::string m = e.what();
    EXPECT_NE(m.find("no block made progress for 50 cycles"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_LE(m.size(), kMaxMessageChars) << m;
    EXPECT_EQ(m.find("doubler"), std::string::npos) << m;
    EXPECT_NE(e.dump().find("doubler: a 2/2 full, b 2/2 full"), std::string::npos) << e.dump();
  }
}

TEST(SimKernel, ChannelMisuseIsReported) {
  Channel<int> c("c", 1);
  c.push(1);
  EXPECT_THROW(c.push(2), CheckFailed);  // one push per cycle
  EXPECT_THROW(c.pop(), CheckFailed);    // nothing committed yet
  c.commit();
  EXPECT_FALSE(c.can_push());
  EXPECT_THROW(Channel<int>("z", 0), InputError);
}

TEST(SimKernel, VcdHasHierarchicalScopesAndValueChanges) {
  std::ostringstream os;
  VcdWriter vcd(os);
  Pipe p(4, 1);
  vcd.add("top.a.valid", 1, [&] { return p.a.can_pop() ? 1u : 0u; });
  vcd.add("top.b.count", 2, [&] { return static_cast<uint64_t>(p.b.size()); });
  p.sim.set_vcd(&vcd);
  p.run(4);
  const std::string v = os.str();
  EXPECT_NE(v.find("$scope module top $end\n$scope module a $end\n$var wire 1 ! valid $end"), std::string::npos) << v;
  EXPECT_NE(v.find("$var wire 2 \" count $end"), std::string::npos) << v;
  EXPECT_NE(v.find("#1\n1!"), std::string::npos) << v;
  EXPECT_NE(v.find("$enddefinitions $end"), std::string::npos);
}

TEST(SimKernel, StatsAsJson) {
  Stats s;
  s.add("cycles", 10);
  s.add("cycles");
  s.sample("latency", 3);
  s.set("pixels_per_clock", 0.5);
  std::ostringstream os;
  s.write_json(os);
  EXPECT_EQ(s.counter("cycles"), 11u);
  EXPECT_NE(os.str().find("\"cycles\": 11"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("\"latency\": ["), std::string::npos) << os.str();
}

}  // namespace
}  // namespace tfu::sim
