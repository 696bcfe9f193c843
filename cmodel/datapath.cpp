#include "cmodel/datapath.hpp"

#include "cmodel/unorm.hpp"

namespace tfu {

// dp::tile_weights_2d (declared in datapath.hpp).
void dp::tile_weights_2d(const TileWeightRom& rom, RomRecon recon, uint32_t fu, uint32_t fv, std::array<int32_t, 16>& w2) {
  const int taps = rom.taps(), m0 = rom.first_tap();
  const unsigned bits = rom.spec().bits;
  std::array<int32_t, 8> wx{}, wy{};
  if (recon == RomRecon::Nearest) {
    rom.weights_nearest(fu, 8, wx.data());
    rom.weights_nearest(fv, 8, wy.data());
  } else {
    rom.weights_linear(fu, 8, 8, wx.data());
    rom.weights_linear(fv, 8, 8, wy.data());
  }
  const auto M = static_cast<int32_t>(unorm::max_code(bits));
  int32_t sum = 0;
  const int centre = -m0;
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i) {
      if (i == centre && j == centre) continue;
      const int32_t w = tile_weight_multiply(wx[static_cast<size_t>(i)], wy[static_cast<size_t>(j)], bits);
      w2[static_cast<size_t>(j * taps + i)] = w;
      sum += w;
    }
  w2[static_cast<size_t>(centre * taps + centre)] = M - sum;
}

}  // namespace tfu
