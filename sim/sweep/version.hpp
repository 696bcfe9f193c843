// The tool's version: the project version and `git describe --always --dirty --tags` of the source
// tree at build time (cmake/TfuVersion.cmake), e.g. "0.1.0 (git 14eff7d-dirty)"; "(unknown)" when
// built outside a git checkout. `tfu --version` prints it and every statistics file records it.
#pragma once

namespace tfu {
const char* tool_version();
}  // namespace tfu
