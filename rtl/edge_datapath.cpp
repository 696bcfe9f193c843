#include "rtl/edge_datapath.hpp"

#include <algorithm>
#include <bit>

#include "cmodel/datapath.hpp"
#include "rtl/median_network.hpp"

namespace tfu::rtl {

namespace {

// The ROMs' contents and the shape decoder (usable directions per 12-bit shape), read once.
struct DirectionTables {
  std::array<const std::array<uint8_t, 256>*, lee_jen::kDirections> rom{};
  std::array<std::array<uint8_t, 2>, lee_jen::kDirections> ends{};  // low-pass endpoints p, q
  std::array<uint32_t, lee_jen::kAllTexels + 1> usable{};
  std::array<uint32_t, 256> choosable{};  // per ROM address: bit i = ROM i's entry is not "never"
};
const DirectionTables& direction_tables() {
  static const DirectionTables kTab = [] {
    DirectionTables t;
    for (const lee_jen::Direction& d : lee_jen::directions()) {
      t.rom[static_cast<size_t>(d.index)] = &lee_jen::direction_weight_rom(d.index);
      t.ends[static_cast<size_t>(d.index)] = {static_cast<uint8_t>(d.p), static_cast<uint8_t>(d.q)};
    }
    for (uint32_t m = 0; m <= lee_jen::kAllTexels; ++m) t.usable[m] = lee_jen::usable_directions(static_cast<lee_jen::TexelMask>(m));
    for (size_t a = 0; a < t.choosable.size(); ++a) t.choosable[a] = lee_jen::choosable_directions(a);
    return t;
  }();
  return kTab;
}

// A min-tree operand as the comparator sees it: {cost[17:0], dir[4:0]} with an invalid operand
// all ones. The right operand of every node has the higher direction indices, so "keep the left
// unless the right is valid and strictly cheaper" (ties -> lower index) is the unsigned minimum.
constexpr uint32_t kInvalidCandidate = UINT32_MAX;
constexpr uint32_t candidate(uint32_t cost, int dir) { return (cost << 5) | static_cast<uint32_t>(dir); }

template <bool kVs16>
void weighted_differences(const DirectionTables& tab, const std::array<Texel4, lee_jen::kTexels>& c,
                          const lee_jen::LowIndex& low, uint32_t usable, size_t addr,
                          std::array<uint32_t, lee_jen::kDirections>& leaf) {
  const TexelFormat fmt = kVs16 ? TexelFormat::VS16X2 : TexelFormat::RGBA8;
  // The texel read for low-pass value n (texel 0 where undefined: such an endpoint is never chosen).
  const auto endpoint = [&](size_t n) -> const Texel4& { return c[static_cast<size_t>(low[n] > 0 ? low[n] - 1 : 0)]; };
  // Every leaf whose direction the shape does not allow, or whose ROM entry says never, is the
  // invalid operand; the model evaluates only the other leaves' multipliers (the same values).
  // (The never flags of the 22 ROM entries at `addr` form the word choosable[addr].)
  leaf.fill(kInvalidCandidate);
  for (uint32_t m = usable & tab.choosable[addr]; m != 0; m &= m - 1) {
    const auto i = static_cast<size_t>(std::countr_zero(m));
    const uint8_t w = (*tab.rom[i])[addr];
    const uint32_t dp = lee_jen::direction_difference(endpoint(tab.ends[i][0]), endpoint(tab.ends[i][1]), fmt);
    leaf[i] = candidate(w * dp, static_cast<int>(i));
  }
}

// Min tree (the comparators of kInvalidCandidate's comment) over the first N entries, level by
// level: 22 -> 11 -> 6 -> 3 -> 2 -> 1; an odd entry out passes to the next level unchanged.
template <size_t N>
void min_tree(std::array<uint32_t, lee_jen::kDirections>& level) {
  if constexpr (N > 1) {
    for (size_t k = 0; k < N / 2; ++k) level[k] = std::min(level[2 * k], level[2 * k + 1]);
    if constexpr (N % 2 == 1) level[N / 2] = level[N - 1];
    min_tree<(N + 1) / 2>(level);
  }
}

}  // namespace

lee_jen::EdgeDecision direction_select(const std::array<Texel4, lee_jen::kTexels>& c, const lee_jen::LowIndex& low,
                                       lee_jen::TexelMask shape, uint32_t fu, uint32_t fv, TexelFormat fmt) {
  const DirectionTables& tab = direction_tables();
  const uint32_t usable = tab.usable[shape & lee_jen::kAllTexels];
  const size_t addr = ((fv >> 4) << 4) | (fu >> 4);
  // Leaves: one ROM and one weighted-difference multiplier per direction; a direction the shape
  // does not allow is the invalid operand (weighted_differences).
  std::array<uint32_t, lee_jen::kDirections> level;
  if (fmt == TexelFormat::VS16X2) {
    weighted_differences<true>(tab, c, low, usable, addr, level);
  } else {
    weighted_differences<false>(tab, c, low, usable, addr, level);
  }
  min_tree<lee_jen::kDirections>(level);
  if (level[0] == kInvalidCandidate) return {0, 0, 0};
  return {static_cast<int>(level[0] & 31u), level[0] >> 5, 0};
}

void EdgeMedian::evaluate() {
  if (!in_.can_pop() || !out_.can_push()) return;
  stage(in_.front(), out_.push_slot());
  in_.pop();
  sim_.progress();
}

void EdgeMedian::stage(const FilterReq& r, EdgeMedianOut& s) {
  s.tag = r.tag;
  const TexelFormat fmt = r.tag.format;
  for (size_t k = 0; k < s.c.size(); ++k) s.c[k] = decode_texel(r.texels[k], fmt);
  s.low = median_network_eval(lee_jen::luma_keys(s.c, r.tag.shape, fmt), r.tag.shape);
}

void EdgeDirection::evaluate() {
  if (!in_.can_pop() || !out_.can_push()) return;
  stage(in_.front(), out_.push_slot());
  in_.pop();
  sim_.progress();
}

void EdgeDirection::stage(const EdgeMedianOut& s, EdgeDirectionOut& o) {
  o.median = s;
  o.direction = direction_select(s.c, s.low, s.tag.shape, s.tag.fu, s.tag.fv, s.tag.format).direction;
  ++chosen[stat_slot(s.tag.req)][static_cast<size_t>(o.direction)];
}

void EdgeMerge::evaluate() {
  if (!in_.can_pop()) return;
  const EdgeDirectionOut& s = in_.front();
  if (s.median.tag.emits() && !out_.can_push()) return;
  Response out;
  if (merge(s, out)) out_.push(out);
  in_.pop();
  sim_.progress();
}

bool EdgeMerge::merge(const EdgeDirectionOut& s, Response& out) {
  const LevelTag& tag = s.median.tag;
  return finish(tag, lee_jen::edge_merge(s.median.c, s.median.low, s.direction, tag.fu, tag.fv, tag.format), out);
}

bool EdgeMerge::finish(const LevelTag& tag, Texel4 c, Response& out) {
  if (tag.holds()) {
    first_ = c;
    return false;
  }
  if (tag.blends) c = dp::level_blend_codes(first_, c, tag.blend);
  if (!probes_.add(tag, c)) return false;
  out = {tag.id, encode_texel(c, tag.format)};
  return true;
}

// edge_stages_fused (software speed only): its plain twin and equality test are named in
// rtl/edge_datapath.hpp.
bool edge_stages_fused(const FilterReq& r, EdgeDirection& direction, EdgeMerge& merge, Response& out) {
  const LevelTag& tag = r.tag;
  const TexelFormat fmt = tag.format;
  std::array<Texel4, lee_jen::kTexels> c;
  for (size_t k = 0; k < c.size(); ++k) c[k] = decode_texel(r.texels[k], fmt);
  const lee_jen::LowIndex low = lee_jen::median_low_pass(lee_jen::luma_keys(c, tag.shape, fmt), tag.shape);
  const int d = lee_jen::select_direction(c, low, tag.shape, tag.fu, tag.fv, fmt).direction;
  ++direction.chosen[stat_slot(tag.req)][static_cast<size_t>(d)];
  return merge.finish(tag, lee_jen::edge_merge(c, low, d, tag.fu, tag.fv, fmt), out);
}

}  // namespace tfu::rtl
