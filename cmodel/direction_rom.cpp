#include "cmodel/direction_rom.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace tfu::lee_jen {
namespace {

const double kRoiAxis = 0.5;                          // horizontal / vertical
const double kRoiDiag = std::sqrt(2.0) / 4.0;         // all diagonals
const double kRoi2x1 = 1.0 / (2.0 * std::sqrt(5.0));  // 26.6 / 63.4 degree directions

// Endpoints as listed in docs/directions.md; orientation (p, q) and axis are derived below.
struct RawDirection {
  int a, b;
  double roi;
};
const RawDirection kRaw[kDirections] = {
    {4, 5, kRoiAxis},  {8, 9, kRoiAxis},  {4, 8, kRoiAxis},   {5, 9, kRoiAxis},    // axis
    {4, 9, kRoiDiag},  {5, 8, kRoiDiag},                                           // centre diagonals
    {1, 5, kRoiDiag},  {2, 4, kRoiDiag},  {3, 8, kRoiDiag},   {4, 7, kRoiDiag},    // outer diagonals
    {5, 10, kRoiDiag}, {6, 9, kRoiDiag},  {8, 12, kRoiDiag},  {9, 11, kRoiDiag},   //
    {3, 9, kRoi2x1},   {7, 5, kRoi2x1},   {4, 10, kRoi2x1},   {8, 6, kRoi2x1},     // 26.6 deg family
    {1, 9, kRoi2x1},   {2, 8, kRoi2x1},   {4, 12, kRoi2x1},   {5, 11, kRoi2x1},    // 63.4 deg family
};

// Blend axis: the axis on which the endpoints' coordinates are exactly {0, 1}; x wins when both
// qualify (the two centre diagonals). Cp is the endpoint at 0 on that axis.
Direction orient(int index, const RawDirection& r) {
  const TexelPos a = texel_pos(r.a), b = texel_pos(r.b);
  const bool x01 = (a.x == 0 && b.x == 1) || (a.x == 1 && b.x == 0);
  const bool y01 = (a.y == 0 && b.y == 1) || (a.y == 1 && b.y == 0);
  if (!x01 && !y01) throw std::logic_error("direction without a {0,1} axis");
  Direction d{index, r.a, r.b, r.roi, x01 ? BlendAxis::X : BlendAxis::Y};
  const int ca = x01 ? a.x : a.y;
  if (ca != 0) std::swap(d.p, d.q);
  return d;
}

uint8_t weight_code(double w) {
  if (!std::isfinite(w)) return kNeverChoose;
  const double c = std::floor(w * (1 << kWeightFracBits) + 0.5);
  return static_cast<uint8_t>(c > kMaxWeightCode ? kMaxWeightCode : c);
}

}  // namespace

std::string Direction::name() const {
  const int lo = p < q ? p : q, hi = p < q ? q : p;
  return fmt::format("C{}-C{}", lo, hi);
}

const char* Direction::family() const {
  if (index < 2) return "horizontal";
  if (index < 4) return "vertical";
  if (index < 6) return "centre-diagonal";
  if (index < 14) return "outer-diagonal";
  return "2x1";
}

const std::array<Direction, kDirections>& directions() {
  static const std::array<Direction, kDirections> kDirs = [] {
    std::array<Direction, kDirections> out{};
    for (int i = 0; i < kDirections; ++i) out[static_cast<size_t>(i)] = orient(i, kRaw[i]);
    return out;
  }();
  return kDirs;
}

double distance_to_direction(int dir, double x, double y) {
  const Direction& d = directions().at(static_cast<size_t>(dir));
  const TexelPos a = texel_pos(d.p), b = texel_pos(d.q);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return std::abs(dy * (x - a.x) - dx * (y - a.y)) / std::sqrt(dx * dx + dy * dy);
}

double exact_weight(int dir, double x, double y) {
  // Eq. 2 with the paper's ||x||: "a very small threshold" so that d == ROI (which happens
  // exactly at some sub-region centres, e.g. the centre diagonals) is never chosen, whatever the
  // floating-point rounding of d.
  const double r = 1.0 - distance_to_direction(dir, x, y) / directions().at(static_cast<size_t>(dir)).roi;
  return r > kNeverChooseThreshold ? 1.0 / r : std::numeric_limits<double>::infinity();
}

const std::array<uint8_t, 256>& direction_weight_rom(int dir) {
  static const std::array<std::array<uint8_t, 256>, kDirections> kRoms = [] {
    std::array<std::array<uint8_t, 256>, kDirections> roms{};
    for (int i = 0; i < kDirections; ++i)
      for (int a = 0; a < 256; ++a) {
        const double x = ((a & 15) + 0.5) / 16.0, y = ((a >> 4) + 0.5) / 16.0;
        roms[static_cast<size_t>(i)][static_cast<size_t>(a)] = weight_code(exact_weight(i, x, y));
      }
    return roms;
  }();
  return kRoms.at(static_cast<size_t>(dir));
}

uint32_t choosable_directions(size_t address) {
  static const std::array<uint32_t, 256> kChoosable = [] {
    std::array<uint32_t, 256> c{};
    for (int i = 0; i < kDirections; ++i) {
      const std::array<uint8_t, 256>& rom = direction_weight_rom(i);
      for (size_t a = 0; a < rom.size(); ++a)
        if (rom[a] != kNeverChoose) c[a] |= 1u << i;
    }
    return c;
  }();
  return kChoosable.at(address);
}

double decode_weight(uint8_t code) {
  if (code == kNeverChoose) return std::numeric_limits<double>::infinity();
  return code / static_cast<double>(1 << kWeightFracBits);
}

std::string KernelShape::name() const {
  if (kind == ShapeKind::Cross) return "cross";
  return fmt::format("{}{}", kind == ShapeKind::T ? 'T' : 'L', rotation);
}

TexelMask rotate_mask(TexelMask m) {
  // Quarter turn clockwise (x right, y down) about (0.5, 0.5): (x, y) -> (1 - y, x).
  TexelMask out = 0;
  for (int n = 1; n <= kTexels; ++n)
    if (m & (1u << (n - 1))) {
      const TexelPos p = texel_pos(n);
      out = static_cast<TexelMask>(out | (1u << (texel_at(1 - p.y, p.x) - 1)));
    }
  return out;
}

const std::vector<KernelShape>& kernel_shapes() {
  static const std::vector<KernelShape> kShapes = [] {
    std::vector<KernelShape> v{{ShapeKind::Cross, 0, kAllTexels}};
    TexelMask t = static_cast<TexelMask>(kAllTexels & ~arm(Side::Top).mask);                            // Fig. 3a
    TexelMask l = static_cast<TexelMask>(kAllTexels & ~(arm(Side::Top).mask | arm(Side::Left).mask));  // Fig. 3b
    for (int r = 0; r < 4; ++r) {
      v.push_back({ShapeKind::T, r, t});
      t = rotate_mask(t);
    }
    for (int r = 0; r < 4; ++r) {
      v.push_back({ShapeKind::L, r, l});
      l = rotate_mask(l);
    }
    return v;
  }();
  return kShapes;
}

uint32_t usable_directions(TexelMask available) {
  uint32_t m = 0;
  for (const Direction& d : directions())
    if ((available >> (d.p - 1) & 1u) && (available >> (d.q - 1) & 1u)) m |= 1u << d.index;
  return m;
}

}  // namespace tfu::lee_jen
