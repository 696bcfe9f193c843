#include "cmodel/temp_paths.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"

namespace tfu {

std::string temp_root() {
  const char* env = std::getenv("TMPDIR");
  return env && *env ? std::string(env) : std::string("/tmp");
}

TempDir::TempDir(const std::string& prefix, const std::string& parent) {
  const std::string root = parent.empty() ? temp_root() : parent;
  std::string name = (std::filesystem::path(root) / (prefix + "-XXXXXX")).string();
  std::vector<char> buf(name.begin(), name.end());
  buf.push_back('\0');
  if (::mkdtemp(buf.data()) == nullptr)
    throw InputError(fmt::format("cannot create a temporary directory in {} (set TMPDIR): {}", quoted_path(root),
                                 std::strerror(errno)));
  path_ = buf.data();
}

TempDir::~TempDir() {
  std::error_code ec;  // removal is best effort: a destructor does not throw
  std::filesystem::remove_all(path_, ec);
}

}  // namespace tfu
