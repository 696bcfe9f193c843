// Shared by the build-time SystemVerilog generators (rtl/sv/svgen.cpp, rtl/sv/edge/svgen_edge.cpp).
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace tfu::svgen {

// Writes `text` to `path` unless the file already holds exactly that text, so that an unchanged
// generated file keeps its timestamp and does not trigger Verilator and Yosys again.
inline void write_if_changed(const std::filesystem::path& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (old == text) return;
    }
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
}

}  // namespace tfu::svgen
