// The unit tests' usual frame: one texture and one sampler, tiled for the unit's cache lines, with
// every request of a trace bound to them (texture 0, sampler 0).
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/scene.hpp"
#include "rtl/unit_config.hpp"

namespace tfu::test {

struct OneTexture {
  Frame frame;
  Trace trace;
};

inline OneTexture one_texture(std::shared_ptr<const Texture> tex, const SamplerDescriptor& s, Trace tr,
                              const rtl::UnitConfig& u) {
  FrameBuilder b(u.cache.line_bytes);
  b.add_texture(std::move(tex), {"test", {}});
  b.add_sampler(s);
  for (TraceRequest& r : tr.requests) r.texture = r.sampler = 0;
  bind_requests(b, tr);
  return {b.finish(), std::move(tr)};
}

inline OneTexture one_texture(const Texture& tex, const SamplerDescriptor& s, Trace tr, const rtl::UnitConfig& u) {
  return one_texture(std::make_shared<const Texture>(tex), s, std::move(tr), u);
}

// A scene mesh's first stage: its texture, and its sampler under filter mode `mode`.
inline OneTexture one_texture(const Mesh& mesh, const char* mode, Trace tr, const rtl::UnitConfig& u) {
  SamplerDescriptor s = mesh.stages[0].sampler;
  s.mode = filter_mode_from_name(mode);
  return one_texture(mesh.stages[0].texture, s, std::move(tr), u);
}

// The message unit_config_from_json gives for a configuration text named "c.json", or "no error".
inline std::string unit_config_error(const std::string& text) {
  try {
    rtl::unit_config_from_json(text, "c.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace tfu::test
