#include "cmodel/scene_frame.hpp"

#include <map>

namespace tfu {

SamplerDescriptor stage_sampler(const TextureStage& stage, bool base_stage, const SceneOverrides& overrides) {
  if (!base_stage) return stage.sampler;
  SamplerDescriptor s = sampler_from_params(overrides.sampler, "sampler overrides", stage.sampler);
  if (overrides.filter) s.mode = *overrides.filter;
  return s;
}

SceneFrame build_scene_frame(const Scene& scene, const SceneOverrides& overrides, int line_bytes) {
  FrameBuilder b(line_bytes);
  SceneFrame sf;
  // Textures and samplers first, in scene order; then the bindings (coefficient textures last).
  std::vector<std::vector<std::pair<int, int>>> raw(scene.meshes.size());
  // With a layout override, one re-laid copy per texture (a texture shared by stages stays one
  // descriptor); its spec records the layout, so that a written trace loads the same frame.
  std::map<const Texture*, std::shared_ptr<const Texture>> relaid;
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t k = 0; k < scene.meshes[m].stages.size(); ++k) {
      const TextureStage& st = scene.meshes[m].stages[k];
      std::shared_ptr<const Texture> tex = st.texture;
      TextureSpec spec = st.spec;
      if (overrides.layout) {
        spec.params["layout"] = memory_layout_name(*overrides.layout);
        if (tex->layout != *overrides.layout) {
          std::shared_ptr<const Texture>& copy = relaid[tex.get()];
          if (!copy) {
            auto t = std::make_shared<Texture>(*tex);
            t->layout = *overrides.layout;
            copy = std::move(t);
          }
          tex = copy;
        }
      }
      raw[m].emplace_back(b.add_texture(tex, std::move(spec)), b.add_sampler(stage_sampler(st, k == 0, overrides)));
    }
  sf.stages.resize(scene.meshes.size());
  for (size_t m = 0; m < raw.size(); ++m)
    for (const auto& [t, s] : raw[m]) sf.stages[m].push_back({b.bind(t, s), s});
  sf.frame = b.finish();
  return sf;
}

Trace loadable_trace(const Frame& frame, Trace trace) {
  for (TraceRequest& r : trace.requests) {
    const int src = frame.textures.at(r.texture).coefficients_of;
    if (src >= 0) r.texture = static_cast<uint16_t>(src);
  }
  describe_frame(frame, trace);
  return trace;
}

}  // namespace tfu
