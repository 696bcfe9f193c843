#include "cmodel/texenv.hpp"

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

TexEnv tex_env_from_name(const std::string& name) {
  for (TexEnv e : {TexEnv::Replace, TexEnv::Modulate, TexEnv::Add, TexEnv::Decal})
    if (name == tex_env_name(e)) return e;
  throw InputError(fmt::format("unknown texture environment '{}' (expected replace, modulate, add or decal)",
                               name.size() <= 60 ? name : name.substr(0, 57) + "..."));
}

const char* tex_env_name(TexEnv e) {
  switch (e) {
    case TexEnv::Replace: return "replace";
    case TexEnv::Modulate: return "modulate";
    case TexEnv::Add: return "add";
    case TexEnv::Decal: return "decal";
  }
  return "?";
}

}  // namespace tfu
