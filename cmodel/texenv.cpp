#include "cmodel/texenv.hpp"

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

TexEnv tex_env_from_name(const std::string& name) { return kTexEnvNames.from_name(name); }
const char* tex_env_name(TexEnv e) { return kTexEnvNames.name(e); }

}  // namespace tfu
