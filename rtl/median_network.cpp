#include "rtl/median_network.hpp"

#include <algorithm>
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

// The pairings above cover exactly the Eq. 4 neighbourhoods of cmodel/lee_jen_geometry.hpp.
constexpr bool same_set(std::array<int, 5> a, std::array<int, 5> b, size_t n) {
  std::sort(a.begin(), a.begin() + static_cast<ptrdiff_t>(n));
  std::sort(b.begin(), b.begin() + static_cast<ptrdiff_t>(n));
  for (size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return false;
  return true;
}
constexpr bool pairings_follow_eq4() {
  for (const lee_jen::BoundaryMedian& g : lee_jen::kBoundaryMedians) {
    bool found = false;
    for (const Median3Spec& m : kMedian3)
      if (m.self == g.self) found = same_set({m.a, m.b, m.c, 0, 0}, {g.self, g.nb[0], g.nb[1], 0, 0}, 3);
    if (!found) return false;
  }
  for (const lee_jen::CentreMedian& g : lee_jen::kCentreMedians) {
    bool found = false;
    for (const Median5Spec& m : kMedian5)
      if (m.self == g.self)
        found = same_set({m.a, m.b, m.c, m.d, m.e}, {g.self, g.centre[0], g.centre[1], g.outer[0], g.outer[1]}, 5);
    if (!found) return false;
  }
  return true;
}
static_assert(pairings_follow_eq4());

constexpr int kMaxWires = 128;
constexpr int kMaxCells = (kMaxWires - kTexels) / 2;

// The netlist in fixed-size arrays, built at compile time so that the evaluator below is
// straight-line code with constant wire numbers.
struct NetlistArrays {
  std::array<CompareCell, kMaxCells> cells{};
  int ncells = 0;
  int wires = kTexels;
  std::array<int, kTexels + 1> out{};
  int depth = 0;
  std::array<int, kMaxWires> depth_of{};  // inputs 0
};

class Builder {
 public:
  NetlistArrays net;
  // Returns (lo, hi) wires of the cell on (a, b), creating it unless a cell on the same two wires
  // exists (shared inputs -> one merged cell).
  constexpr std::pair<int, int> cell(int a, int b) {
    const auto key = std::minmax(a, b);
    for (int i = 0; i < net.ncells; ++i) {
      const CompareCell& c = net.cells[static_cast<size_t>(i)];
      if (std::minmax(c.in_a, c.in_b) == key) return {c.lo, c.hi};
    }
    if (net.ncells == kMaxCells) throw CheckFailed("median network: more cells than the evaluator holds");
    const int lo = net.wires++, hi = net.wires++;
    net.cells[static_cast<size_t>(net.ncells++)] = {a, b, lo, hi};
    const int d = std::max(net.depth_of[static_cast<size_t>(a)], net.depth_of[static_cast<size_t>(b)]) + 1;
    net.depth_of[static_cast<size_t>(lo)] = net.depth_of[static_cast<size_t>(hi)] = d;
    net.depth = std::max(net.depth, d);
    return {lo, hi};
  }
  // median3 = max(min(a, b), min(max(a, b), c)).
  constexpr int median3(int a, int b, int c) {
    const auto [lo, hi] = cell(a, b);
    const int m = cell(hi, c).first;
    return cell(lo, m).second;
  }
  // median5 = median3 of e, max(min(a,b), min(c,d)) and min(max(a,b), max(c,d)).
  constexpr int median5(int a, int b, int c, int d, int e) {
    const auto [l1, h1] = cell(a, b);
    const auto [l2, h2] = cell(c, d);
    const int x = cell(l1, l2).second;
    const int y = cell(h1, h2).first;
    return median3(x, y, e);
  }
};

constexpr int wire(int texel) { return texel - 1; }

constexpr NetlistArrays build_netlist() {
  Builder b;
  for (const Median3Spec& m : kMedian3) b.net.out[static_cast<size_t>(m.self)] = b.median3(wire(m.a), wire(m.b), wire(m.c));
  for (const Median5Spec& m : kMedian5)
    b.net.out[static_cast<size_t>(m.self)] = b.median5(wire(m.a), wire(m.b), wire(m.c), wire(m.d), wire(m.e));
  return b.net;
}
constexpr NetlistArrays kNetlist = build_netlist();

// One compare cell with its wires as constants.
template <size_t I>
inline void compare_cell(std::array<int32_t, kMaxWires>& w) {
  constexpr CompareCell c = kNetlist.cells[I];
  const int32_t a = w[static_cast<size_t>(c.in_a)], b = w[static_cast<size_t>(c.in_b)];
  w[static_cast<size_t>(c.lo)] = std::min(a, b);
  w[static_cast<size_t>(c.hi)] = std::max(a, b);
}
template <size_t... I>
inline void compare_cells(std::array<int32_t, kMaxWires>& w, std::index_sequence<I...>) {
  (compare_cell<I>(w), ...);  // in topological order
}

}  // namespace

const MedianNetlist& median_netlist() {
  static const MedianNetlist net = [] {
    MedianNetlist n;
    n.wires = kNetlist.wires;
    n.cells.assign(kNetlist.cells.begin(), kNetlist.cells.begin() + kNetlist.ncells);
    n.out = kNetlist.out;
    n.depth = kNetlist.depth;
    return n;
  }();
  return net;
}

std::array<int32_t, kTexels> median_input_select(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape) {
  std::array<int32_t, kTexels> in{};
  for (int n = 1; n <= kTexels; ++n) in[static_cast<size_t>(wire(n))] = key[static_cast<size_t>(n)];
  const auto has = [shape](int n) { return lee_jen::has_texel(shape, n); };
  for (const lee_jen::CentreMedian& c : lee_jen::kCentreMedians) {
    const int o1 = c.outer[0], o2 = c.outer[1];
    const bool h1 = has(o1), h2 = has(o2);
    if (h1 && h2) continue;
    if (h1 || h2) {  // T: the missing outer neighbour is replaced by the opposite centre texel
      in[static_cast<size_t>(wire(h1 ? o2 : o1))] = key[static_cast<size_t>(c.opposite)];
    } else {  // L corner: +inf and -inf leave the median of the other three
      in[static_cast<size_t>(wire(o1))] = kKeyPlusInfinity;
      in[static_cast<size_t>(wire(o2))] = kKeyMinusInfinity;
    }
  }
  return in;
}

lee_jen::LowIndex median_network_eval(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape) {
  std::array<int32_t, kMaxWires> w;  // wires (12 inputs + 2 per cell), each written before it is read
  const std::array<int32_t, kTexels> in = median_input_select(key, shape);
  std::copy(in.begin(), in.end(), w.begin());
  compare_cells(w, std::make_index_sequence<static_cast<size_t>(kNetlist.ncells)>{});
  lee_jen::LowIndex low{};
  for (int n = 1; n <= kTexels; ++n)
    if ((shape >> (n - 1)) & 1u) low[static_cast<size_t>(n)] = w[static_cast<size_t>(kNetlist.out[static_cast<size_t>(n)])] & 15;
  return low;
}

}  // namespace tfu::rtl
