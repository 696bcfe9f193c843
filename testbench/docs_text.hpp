// The text of a file of docs/, for the tests that check a generated block is pasted there (empty when
// the file cannot be read, so that the block is not found and the test fails).
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace tfu::test {

inline std::string docs_text(const std::string& name) {
  std::ifstream f(std::string(TFU_DOCS_DIR) + "/" + name);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace tfu::test
