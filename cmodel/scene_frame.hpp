// A scene's frame as the driver sets it up for the unit (frame.hpp): every stage's texture placed
// in the texel memory, every stage's sampler in the descriptor table, and which descriptors each
// stage of each mesh requests (a bspline-interp stage: its texture's coefficient texture).
//
// Command-line overrides (`--filter`, `--shape-policy`, `--max-aniso`) replace the sampler fields of
// each mesh's first (base) stage only: the other stages (a light map) keep their own samplers.
#pragma once

#include <optional>
#include <vector>

#include "cmodel/frame.hpp"
#include "cmodel/scene.hpp"

namespace tfu {

struct StageBinding {
  int texture = 0;  // texture descriptor the stage's requests name (bound: FrameBuilder::bind)
  int sampler = 0;  // sampler descriptor
};

struct SceneOverrides {
  std::optional<FilterMode> filter;  // the base stage's filter mode
  Params sampler;                    // further sampler keys of the base stage (bindings.hpp)
  // The memory layout of every texture of every stage (level textures included); nullopt: each
  // texture's own. A tiled texture is tiled for the unit's cache line (FrameBuilder).
  std::optional<MemoryLayout> layout;
};

struct SceneFrame {
  Frame frame;
  std::vector<std::vector<StageBinding>> stages;  // [mesh][stage]
};

SceneFrame build_scene_frame(const Scene& scene, const SceneOverrides& overrides, int line_bytes = 64);
// The sampler a stage uses after the overrides.
SamplerDescriptor stage_sampler(const TextureStage& stage, bool base_stage, const SceneOverrides& overrides);

// A trace of descriptor indices as a file records it: coefficient textures back to their source
// texture (frame_from_trace makes them again) and header lines describing the frame's textures and
// samplers (describe_frame).
Trace loadable_trace(const Frame& frame, Trace trace);

}  // namespace tfu
