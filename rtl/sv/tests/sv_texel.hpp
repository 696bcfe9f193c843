// Texel packing shared by the Verilator equivalence tests: an RGBA8 datapath texel (channels
// 0..255) as the 32-bit word of the SystemVerilog ports, channel k in bits [8k+7:8k].
#pragma once

#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "cmodel/texture.hpp"

namespace tfu::svtest {

inline uint32_t pack(const Texel4& c) {
  return static_cast<uint32_t>(c[0]) | static_cast<uint32_t>(c[1]) << 8 | static_cast<uint32_t>(c[2]) << 16 |
         static_cast<uint32_t>(c[3]) << 24;
}
inline Texel4 unpack(uint32_t w) {
  return {static_cast<int32_t>(w & 255), static_cast<int32_t>((w >> 8) & 255), static_cast<int32_t>((w >> 16) & 255),
          static_cast<int32_t>(w >> 24)};
}
inline std::string str(const Texel4& c) { return fmt::format("({},{},{},{})", c[0], c[1], c[2], c[3]); }

}  // namespace tfu::svtest
