#include "cmodel/signed_formats.hpp"

namespace tfu::snorm {

const std::array<int32_t, 65536>& mul_table() {
  static const std::array<int32_t, 65536> kTable = [] {
    std::array<int32_t, 65536> t{};
    for (int r1 = 0; r1 < 256; ++r1)
      for (int r2 = 0; r2 < 256; ++r2)
        t[static_cast<size_t>(r1 * 256 + r2)] = mul_table_entry(static_cast<uint8_t>(r1), static_cast<uint8_t>(r2));
    return t;
  }();
  return kTable;
}

}  // namespace tfu::snorm
