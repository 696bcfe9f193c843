#include "rtl/median_network.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "cmodel/error.hpp"

namespace tfu::rtl {
namespace {

using lee_jen::kTexels;

// Which input pair each median compares first (and the remaining inputs), chosen so that eight
// pairs serve all sixteen uses: (1,2) M1 M2; (11,12) M11 M12; (4,5) M4 M5; (8,9) M8 M9;
// (3,8) M4 M7; (4,7) M3 M8; (6,9) M5 M10; (5,10) M6 M9.
struct Median3Spec {
  int self, a, b, c;  // pair (a, b), then c
};
constexpr std::array<Median3Spec, 8> kMedian3{{
    {1, 1, 2, 4}, {2, 1, 2, 5}, {3, 4, 7, 3}, {7, 3, 8, 7}, {6, 5, 10, 6}, {10, 6, 9, 10}, {11, 11, 12, 8}, {12, 11, 12, 9}}};
struct Median5Spec {
  int self, a, b, c, d, e;  // pairs (a, b) and (c, d), then e
};
constexpr std::array<Median5Spec, 4> kMedian5{{
    {4, 4, 5, 3, 8, 1}, {5, 4, 5, 6, 9, 2}, {8, 8, 9, 4, 7, 11}, {9, 8, 9, 5, 10, 12}}};

// Centre texel, its two outer neighbours (o1, o2) and the diagonally opposite centre texel (Sec. 3).
struct CentreOuter {
  int self, o1, o2, opposite;
};
constexpr std::array<CentreOuter, 4> kCentreOuter{{{4, 1, 3, 9}, {5, 2, 6, 8}, {8, 7, 11, 5}, {9, 10, 12, 4}}};

class Builder {
 public:
  MedianNetlist net;
  std::vector<int> depth_of;
  Builder() {
    net.wires = kTexels;
    depth_of.assign(kTexels, 0);
  }
  // Returns (lo, hi) wires of the cell on (a, b), creating it unless a cell on the same two wires
  // exists (shared inputs -> one merged cell).
  std::pair<int, int> cell(int a, int b) {
    const auto key = std::minmax(a, b);
    const auto it = cells_.find(key);
    if (it != cells_.end()) return it->second;
    const int lo = net.wires++, hi = net.wires++;
    net.cells.push_back({a, b, lo, hi});
    const int d = std::max(depth_of[static_cast<size_t>(a)], depth_of[static_cast<size_t>(b)]) + 1;
    depth_of.push_back(d);
    depth_of.push_back(d);
    net.depth = std::max(net.depth, d);
    return cells_[key] = {lo, hi};
  }
  // median3 = max(min(a, b), min(max(a, b), c)).
  int median3(int a, int b, int c) {
    const auto [lo, hi] = cell(a, b);
    const int m = cell(hi, c).first;
    return cell(lo, m).second;
  }
  // median5 = median3 of e, max(min(a,b), min(c,d)) and min(max(a,b), max(c,d)).
  int median5(int a, int b, int c, int d, int e) {
    const auto [l1, h1] = cell(a, b);
    const auto [l2, h2] = cell(c, d);
    const int x = cell(l1, l2).second;
    const int y = cell(h1, h2).first;
    return median3(x, y, e);
  }

 private:
  std::map<std::pair<int, int>, std::pair<int, int>> cells_;
};

constexpr int wire(int texel) { return texel - 1; }
constexpr int kMaxWires = 128;

}  // namespace

const MedianNetlist& median_netlist() {
  static const MedianNetlist net = [] {
    Builder b;
    for (const Median3Spec& m : kMedian3) b.net.out[static_cast<size_t>(m.self)] = b.median3(wire(m.a), wire(m.b), wire(m.c));
    for (const Median5Spec& m : kMedian5)
      b.net.out[static_cast<size_t>(m.self)] = b.median5(wire(m.a), wire(m.b), wire(m.c), wire(m.d), wire(m.e));
    if (b.net.wires > kMaxWires) throw CheckFailed("median network: more wires than the evaluator holds");
    return b.net;
  }();
  return net;
}

std::array<int32_t, kTexels> median_input_select(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape) {
  std::array<int32_t, kTexels> in{};
  for (int n = 1; n <= kTexels; ++n) in[static_cast<size_t>(wire(n))] = key[static_cast<size_t>(n)];
  const auto has = [shape](int n) { return ((shape >> (n - 1)) & 1u) != 0; };
  for (const CentreOuter& c : kCentreOuter) {
    const bool h1 = has(c.o1), h2 = has(c.o2);
    if (h1 && h2) continue;
    if (h1 || h2) {  // T: the missing outer neighbour is replaced by the opposite centre texel
      in[static_cast<size_t>(wire(h1 ? c.o2 : c.o1))] = key[static_cast<size_t>(c.opposite)];
    } else {  // L corner: +inf and -inf leave the median of the other three
      in[static_cast<size_t>(wire(c.o1))] = kKeyPlusInfinity;
      in[static_cast<size_t>(wire(c.o2))] = kKeyMinusInfinity;
    }
  }
  return in;
}

lee_jen::LowIndex median_network_eval(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape) {
  const MedianNetlist& net = median_netlist();
  std::array<int32_t, kMaxWires> w;  // wires (12 inputs + 2 per cell), each written before it is read
  const std::array<int32_t, kTexels> in = median_input_select(key, shape);
  std::copy(in.begin(), in.end(), w.begin());
  for (const CompareCell& c : net.cells) {
    const int32_t a = w[static_cast<size_t>(c.in_a)], b = w[static_cast<size_t>(c.in_b)];
    w[static_cast<size_t>(c.lo)] = std::min(a, b);
    w[static_cast<size_t>(c.hi)] = std::max(a, b);
  }
  lee_jen::LowIndex low{};
  for (int n = 1; n <= kTexels; ++n)
    if ((shape >> (n - 1)) & 1u) low[static_cast<size_t>(n)] = w[static_cast<size_t>(net.out[static_cast<size_t>(n)])] & 15;
  return low;
}

}  // namespace tfu::rtl
