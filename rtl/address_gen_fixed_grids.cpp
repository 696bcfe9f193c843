// The address generator's per-wrap-pair grids: LINEAR, the edge cross and CUBIC of a 4-tap weight
// ROM with both wrap modes fixed at compile time, one function per pair, chosen per sampler
// descriptor at reset
// (AddressGen::fixed_wrap_grid). Software speed only: the plain unit is AddressGen::grid_any
// in rtl/address_gen.cpp, which reads the wrap modes at run time; these must form the same grid
// (TfuUnit.FixedWrapGridsEqualThePlainAddressUnit compares them over every wrap pair, level
// sizes and probe offsets). Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the
// CLI's --plain): every descriptor then takes grid_any.
#include "cmodel/datapath_fast.hpp"
#include "rtl/address_gen.hpp"
#include "rtl/address_gen_detail.hpp"

namespace tfu::rtl {

using detail::cells_inside;
using detail::probe_coord;

// LINEAR (columns i0, i0 + 1 and rows j0, j0 + 1), the edge cross (columns and rows -1..2
// around the centre square, grid_any's EdgePreserving case) and CUBIC with T = 4 taps (columns and
// rows from i0 + m0, m0 = 1 - T/2 = -1: grid_any's Cubic case) through the wrap unit of each axis
// with the modes fixed (dp::fast::wrap_taps): the same grid as grid_any's.
template <WrapMode kWs, WrapMode kWt, AddressGen::FixedGrid kShape>
void AddressGen::grid_fixed(const SamplerDescriptor&, int, int, FootprintReq& f, int w, int h, float s, float t,
                            const ProbeLevelOffset* o) {
  constexpr bool kCross = kShape == FixedGrid::Cross;
  constexpr int kTaps = kShape == FixedGrid::Linear ? 2 : 4, kFirst = kShape == FixedGrid::Linear ? 0 : -1;
  const dp::LevelCoord u = probe_coord(s, w, o, o ? o->du_q8 : 0), v = probe_coord(t, h, o, o ? o->dv_q8 : 0);
  f.tag.fu = u.f;
  f.tag.fv = v.f;
  int col[kTaps], row[kTaps];
  dp::fast::wrap_taps<kWs, kTaps>(u.i0 + kFirst, w, col);
  dp::fast::wrap_taps<kWt, kTaps>(v.i0 + kFirst, h, row);
  TapGrid& g = f.grid;
  g.cols = g.rows = kTaps;
  for (size_t i = 0; i < kTaps; ++i) {
    g.x[i] = static_cast<int16_t>(col[i]);
    g.y[i] = static_cast<int16_t>(row[i]);
  }
  f.cross = kCross;
  g.used = kCross ? cross_cells(lee_jen::kAllTexels) : square_cells(kTaps, kTaps);
  if constexpr (kWs == WrapMode::ClampToBorder || kWt == WrapMode::ClampToBorder)
    g.used = static_cast<uint16_t>(g.used & cells_inside(g));
}

template <AddressGen::FixedGrid kShape, size_t... k>
AddressGen::GridFn AddressGen::fixed_grid(size_t wrap_pair, std::index_sequence<k...>) {
  static constexpr GridFn kTable[] = {&grid_fixed<static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4), kShape>...};
  return kTable[wrap_pair];
}

// The LINEAR quad path's four grids (AddressGen::quad_grid_function): grid_fixed's Linear shape,
// inlined four times (flatten) with no probe offset.
template <WrapMode kWs, WrapMode kWt>
[[gnu::flatten]] void AddressGen::grid_linear_quad(FootprintReq* f, int w, int h, const float* s, const float* t) {
  const SamplerDescriptor unused{};  // grid_fixed's Linear shape reads no descriptor field
  for (size_t k = 0; k < 4; ++k) grid_fixed<kWs, kWt, FixedGrid::Linear>(unused, 2, 0, f[k], w, h, s[k], t[k], nullptr);
}

template <size_t... k>
AddressGen::QuadGridFn AddressGen::linear_quad_grid(size_t wrap_pair, std::index_sequence<k...>) {
  static constexpr QuadGridFn kTable[] = {&grid_linear_quad<static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)>...};
  return kTable[wrap_pair];
}

AddressGen::QuadGridFn AddressGen::linear_quad_grid(WrapMode wrap_s, WrapMode wrap_t) {
  const auto pair = static_cast<size_t>(4 * static_cast<int>(wrap_s) + static_cast<int>(wrap_t));
  return linear_quad_grid(pair, std::make_index_sequence<16>());
}

AddressGen::GridFn AddressGen::fixed_wrap_grid(FixedGrid shape, WrapMode wrap_s, WrapMode wrap_t) {
  const auto pair = static_cast<size_t>(4 * static_cast<int>(wrap_s) + static_cast<int>(wrap_t));
  switch (shape) {
    case FixedGrid::Linear: return fixed_grid<FixedGrid::Linear>(pair, std::make_index_sequence<16>());
    case FixedGrid::Cross: return fixed_grid<FixedGrid::Cross>(pair, std::make_index_sequence<16>());
    case FixedGrid::Cubic4: break;
  }
  return fixed_grid<FixedGrid::Cubic4>(pair, std::make_index_sequence<16>());
}

}  // namespace tfu::rtl
