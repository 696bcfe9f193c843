#include "rtl/median_network.hpp"

#include <algorithm>
#include <utility>

#include "cmodel/error.hpp"

namespace tfu::rtl {
namespace {

using lee_jen::kTexels;

constexpr int kMaxWires = 128;
constexpr int kMaxCells = 56;
constexpr int kMaxSelects = kTexels;

// The netlist in fixed-size arrays, built at compile time so that the evaluator below is
// straight-line code with constant wire numbers.
struct NetlistArrays {
  std::array<CompareCell, kMaxCells> cells{};
  int ncells = 0;
  std::array<Median3Select, kMaxSelects> selects{};
  int nselects = 0;
  int wires = kTexels;
  std::array<int, kTexels + 1> out{};
  int depth = 0;
  std::array<int, kMaxWires> depth_of{};     // cells on the longest path to the wire (inputs 0)
  std::array<bool, kMaxWires> selected{};    // driven by a selector
  std::array<bool, kMaxWires> read{};        // read by a cell, a selector or an output
};

class Builder {
 public:
  NetlistArrays net;
  // Index of the cell on wires (a, b), created unless a cell on the same two wires exists (shared
  // inputs -> one merged cell). Inputs in wire order.
  constexpr int cell(int a, int b) {
    if (a > b) std::swap(a, b);
    if (net.selected[static_cast<size_t>(a)] || net.selected[static_cast<size_t>(b)])
      throw CheckFailed("median network: a compare cell would read a selector");
    for (int i = 0; i < net.ncells; ++i) {
      const CompareCell& c = net.cells[static_cast<size_t>(i)];
      if (c.in_a == a && c.in_b == b) return i;
    }
    if (net.ncells == kMaxCells || net.wires + 2 > kMaxWires) throw CheckFailed("median network: more cells than the evaluator holds");
    const int lo = net.wires++, hi = net.wires++;
    net.cells[static_cast<size_t>(net.ncells)] = {a, b, lo, hi};
    const int d = std::max(net.depth_of[static_cast<size_t>(a)], net.depth_of[static_cast<size_t>(b)]) + 1;
    net.depth_of[static_cast<size_t>(lo)] = net.depth_of[static_cast<size_t>(hi)] = d;
    net.depth = std::max(net.depth, d);
    return net.ncells++;
  }
  constexpr const CompareCell& at(int i) const { return net.cells[static_cast<size_t>(i)]; }
  // Three-point median (Lee & Jen Sec. 6): three cells in parallel, a selector on their flags.
  constexpr int median3(int a, int b, int c) {
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    const int ab = cell(a, b), ac = cell(a, c), bc = cell(b, c);
    if (net.nselects == kMaxSelects || net.wires == kMaxWires) throw CheckFailed("median network: more selectors than the evaluator holds");
    const int out = net.wires++;
    net.selects[static_cast<size_t>(net.nselects++)] = {a, b, c, ab, ac, bc, out};
    net.selected[static_cast<size_t>(out)] = true;
    net.depth_of[static_cast<size_t>(out)] = std::max({net.depth_of[static_cast<size_t>(at(ab).lo)],
                                                       net.depth_of[static_cast<size_t>(at(ac).lo)],
                                                       net.depth_of[static_cast<size_t>(at(bc).lo)]});
    return out;
  }
  // Five-point median: cells on the pairs p and q; the max of their minima and the min of their
  // maxima (the extremes of the four dropped); the three-point median of those two and e.
  constexpr int median5(std::array<int, 2> p, std::array<int, 2> q, int e) {
    const CompareCell cp = at(cell(p[0], p[1])), cq = at(cell(q[0], q[1]));
    const int max_of_minima = at(cell(cp.lo, cq.lo)).hi;
    const int min_of_maxima = at(cell(cp.hi, cq.hi)).lo;
    return median3(max_of_minima, min_of_maxima, e);
  }
  constexpr void mark_reads() {
    const auto mark = [this](int w) { net.read[static_cast<size_t>(w)] = true; };
    for (int i = 0; i < net.ncells; ++i) {
      mark(at(i).in_a);
      mark(at(i).in_b);
    }
    for (int i = 0; i < net.nselects; ++i) {
      const Median3Select& s = net.selects[static_cast<size_t>(i)];
      mark(s.a);
      mark(s.b);
      mark(s.c);
    }
    for (int n = 1; n <= kTexels; ++n) mark(net.out[static_cast<size_t>(n)]);
  }
};

constexpr int wire(int texel) { return texel - 1; }

// The centre neighbour of a centre texel that is diagonal to its outer neighbour o (C4, C1 -> C5).
constexpr int diagonal_partner(const lee_jen::CentreMedian& m, int o) {
  for (const int c : m.centre) {
    const lee_jen::TexelPos pc = lee_jen::texel_pos(c), po = lee_jen::texel_pos(o);
    if ((pc.x - po.x) * (pc.x - po.x) == 1 && (pc.y - po.y) * (pc.y - po.y) == 1) return c;
  }
  throw CheckFailed("median network: no centre neighbour diagonal to an outer neighbour");
}

// Eq. 4 (cmodel/lee_jen_geometry.hpp): three-point medians first, so that the five-point medians'
// first-level pairs find their cells.
constexpr NetlistArrays build_netlist() {
  Builder b;
  for (const lee_jen::BoundaryMedian& m : lee_jen::kBoundaryMedians)
    b.net.out[static_cast<size_t>(m.self)] = b.median3(wire(m.self), wire(m.nb[0]), wire(m.nb[1]));
  for (const lee_jen::CentreMedian& m : lee_jen::kCentreMedians) {
    const int o1 = m.outer[0], o2 = m.outer[1];
    b.net.out[static_cast<size_t>(m.self)] = b.median5({wire(o1), wire(diagonal_partner(m, o1))},
                                                       {wire(o2), wire(diagonal_partner(m, o2))}, wire(m.self));
  }
  b.mark_reads();
  return b.net;
}
constexpr NetlistArrays kNetlist = build_netlist();

// One compare cell with its wires as constants; lo and hi are written only where they are read.
template <size_t I>
inline void compare_cell(std::array<int32_t, kMaxWires>& w, std::array<bool, kMaxCells>& a_gt_b) {
  constexpr CompareCell c = kNetlist.cells[I];
  const int32_t a = w[static_cast<size_t>(c.in_a)], b = w[static_cast<size_t>(c.in_b)];
  a_gt_b[I] = a > b;
  if constexpr (kNetlist.read[static_cast<size_t>(c.lo)]) w[static_cast<size_t>(c.lo)] = std::min(a, b);
  if constexpr (kNetlist.read[static_cast<size_t>(c.hi)]) w[static_cast<size_t>(c.hi)] = std::max(a, b);
}
template <size_t... I>
inline void compare_cells(std::array<int32_t, kMaxWires>& w, std::array<bool, kMaxCells>& a_gt_b, std::index_sequence<I...>) {
  (compare_cell<I>(w, a_gt_b), ...);  // in topological order
}
// One three-point selector: b if a > b == b > c, else a if a > b != a > c, else c.
template <size_t I>
inline void median3_select(std::array<int32_t, kMaxWires>& w, const std::array<bool, kMaxCells>& a_gt_b) {
  constexpr Median3Select s = kNetlist.selects[I];
  const bool ab = a_gt_b[static_cast<size_t>(s.ab)], ac = a_gt_b[static_cast<size_t>(s.ac)], bc = a_gt_b[static_cast<size_t>(s.bc)];
  w[static_cast<size_t>(s.out)] = ab == bc ? w[static_cast<size_t>(s.b)] : (ab != ac ? w[static_cast<size_t>(s.a)] : w[static_cast<size_t>(s.c)]);
}
template <size_t... I>
inline void median3_selects(std::array<int32_t, kMaxWires>& w, const std::array<bool, kMaxCells>& a_gt_b,
                            std::index_sequence<I...>) {
  (median3_select<I>(w, a_gt_b), ...);
}

}  // namespace

const MedianNetlist& median_netlist() {
  static const MedianNetlist net = [] {
    MedianNetlist n;
    n.wires = kNetlist.wires;
    n.cells.assign(kNetlist.cells.begin(), kNetlist.cells.begin() + kNetlist.ncells);
    n.selects.assign(kNetlist.selects.begin(), kNetlist.selects.begin() + kNetlist.nselects);
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
  // Per centre texel, its two outer neighbours' inputs: the key when present; a T's missing one
  // takes the opposite centre texel's key; an L corner's missing pair +inf and -inf, which leave
  // the median of the other three. (Each outer texel belongs to one centre texel; selects, so
  // that the model does not branch on the shape.)
  for (const lee_jen::CentreMedian& c : lee_jen::kCentreMedians) {
    const int o1 = c.outer[0], o2 = c.outer[1];
    const bool h1 = has(o1), h2 = has(o2);
    const int32_t opposite = key[static_cast<size_t>(c.opposite)];
    int32_t& in1 = in[static_cast<size_t>(wire(o1))];
    int32_t& in2 = in[static_cast<size_t>(wire(o2))];
    in1 = h1 ? in1 : (h2 ? opposite : kKeyPlusInfinity);
    in2 = h2 ? in2 : (h1 ? opposite : kKeyMinusInfinity);
  }
  return in;
}

lee_jen::LowIndex median_network_eval(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape) {
  std::array<int32_t, kMaxWires> w;  // wires (12 inputs, 2 per cell, 1 per selector), written before read
  std::array<bool, kMaxCells> a_gt_b;  // the cells' flags
  const std::array<int32_t, kTexels> in = median_input_select(key, shape);
  std::copy(in.begin(), in.end(), w.begin());
  compare_cells(w, a_gt_b, std::make_index_sequence<static_cast<size_t>(kNetlist.ncells)>{});
  median3_selects(w, a_gt_b, std::make_index_sequence<static_cast<size_t>(kNetlist.nselects)>{});
  lee_jen::LowIndex low{};
  for (int n = 1; n <= kTexels; ++n)  // texels outside the shape have no low-pass value (0)
    low[static_cast<size_t>(n)] =
        w[static_cast<size_t>(kNetlist.out[static_cast<size_t>(n)])] & 15 & -static_cast<int32_t>((shape >> (n - 1)) & 1u);
  return low;
}

}  // namespace tfu::rtl
