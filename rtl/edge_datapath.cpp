#include "rtl/edge_datapath.hpp"

#include "cmodel/datapath.hpp"
#include "rtl/median_network.hpp"

namespace tfu::rtl {

lee_jen::EdgeDecision direction_select(const std::array<Texel4, lee_jen::kTexels>& c, const lee_jen::LowIndex& low,
                                       lee_jen::TexelMask shape, uint32_t xf, uint32_t yf, TexelFormat fmt) {
  struct Candidate {
    bool valid;
    uint32_t cost;  // [17:0]
    int dir;        // [4:0]
  };
  // The ROMs' contents and the shape decoder (usable directions per 12-bit shape), read once.
  struct Tables {
    std::array<const std::array<uint8_t, 256>*, lee_jen::kDirections> rom{};
    std::array<std::array<int, 2>, lee_jen::kDirections> ends{};
    std::array<uint32_t, lee_jen::kAllTexels + 1> usable{};
  };
  static const Tables kTab = [] {
    Tables t;
    for (const lee_jen::Direction& d : lee_jen::directions()) {
      t.rom[static_cast<size_t>(d.index)] = &lee_jen::direction_weight_rom(d.index);
      t.ends[static_cast<size_t>(d.index)] = {d.p, d.q};
    }
    for (uint32_t m = 0; m <= lee_jen::kAllTexels; ++m) t.usable[m] = lee_jen::usable_directions(static_cast<lee_jen::TexelMask>(m));
    return t;
  }();
  const uint32_t usable = kTab.usable[shape & lee_jen::kAllTexels];
  const size_t addr = ((yf >> 4) << 4) | (xf >> 4);
  const auto lowv = [&](int n) -> const Texel4& { return c[static_cast<size_t>(low[static_cast<size_t>(n)] - 1)]; };
  // Leaves: one ROM and one weighted-difference multiplier per direction.
  std::array<Candidate, lee_jen::kDirections> level;  // every entry written below
  for (int i = 0; i < lee_jen::kDirections; ++i) {
    const auto& ends = kTab.ends[static_cast<size_t>(i)];
    const uint8_t w = (*kTab.rom[static_cast<size_t>(i)])[addr];
    const bool valid = ((usable >> i) & 1u) && w != lee_jen::kNeverChoose;
    level[static_cast<size_t>(i)] = {valid, valid ? w * lee_jen::direction_difference(lowv(ends[0]), lowv(ends[1]), fmt) : 0, i};
  }
  // Min tree: each node keeps its left input unless the right one is valid and strictly cheaper,
  // so ties go to the lower direction index.
  size_t n = lee_jen::kDirections;
  while (n > 1) {
    for (size_t k = 0; k < n / 2; ++k) {
      const Candidate& a = level[2 * k];
      const Candidate& b = level[2 * k + 1];
      level[k] = (b.valid && (!a.valid || b.cost < a.cost)) ? b : a;
    }
    if (n % 2) level[n / 2] = level[n - 1];
    n = (n + 1) / 2;
  }
  return {level[0].valid ? level[0].dir : 0, level[0].cost, 0};
}

void EdgeMedian::evaluate() {
  if (!in_.can_pop() || !out_.can_push()) return;
  const FilterReq& r = in_.front();
  EdgeS1& s = out_.push_slot();
  s.tag = r.tag;
  for (size_t k = 0; k < s.c.size(); ++k) s.c[k] = decode_texel(r.texels[k], fmt_);
  s.low = median_network_eval(lee_jen::luma_keys(s.c, r.tag.shape, fmt_), r.tag.shape);
  in_.pop();
  sim_.progress();
}

void EdgeDirection::evaluate() {
  if (!in_.can_pop() || !out_.can_push()) return;
  const EdgeS1& s = in_.front();
  EdgeS2& o = out_.push_slot();
  o.s1 = s;
  o.direction = direction_select(s.c, s.low, s.tag.shape, s.tag.fu, s.tag.fv, fmt_).direction;
  ++chosen[static_cast<size_t>(o.direction)];
  in_.pop();
  sim_.progress();
}

void EdgeMerge::evaluate() {
  if (!in_.can_pop()) return;
  const EdgeS2& s = in_.front();
  const LevelTag& tag = s.s1.tag;
  if (tag.emits() && !out_.can_push()) return;
  Texel4 c = lee_jen::edge_merge(s.s1.c, s.s1.low, s.direction, tag.fu, tag.fv, fmt_);
  if (tag.holds()) {
    first_ = c;
  } else {
    if (tag.two) c = dp::level_blend(first_, c, tag.blend);
    out_.push({tag.id, encode_texel(c, fmt_)});
  }
  in_.pop();
  sim_.progress();
}

}  // namespace tfu::rtl
