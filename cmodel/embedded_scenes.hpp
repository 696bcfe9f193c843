// Built-in scene files compiled into the library: the table is generated at build time by
// cmake/TfuEmbedScenes.cmake from cmodel/scenes/*.json and read by cmodel/scene.cpp.
#pragma once

#include <cstddef>

namespace tfu::detail {
struct EmbeddedScene {
  const char* name;
  const char* json;
};
extern const EmbeddedScene kEmbeddedScenes[];
extern const size_t kEmbeddedSceneCount;
}  // namespace tfu::detail
