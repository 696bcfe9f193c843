#include "cmodel/golden_unit.hpp"

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

const Sampler& GoldenUnit::build(int texture, int sampler) const {
  const std::lock_guard lock(mutex_);
  auto& slot = slots_.at(static_cast<size_t>(texture) * frame_.regs.samplers.size() + static_cast<size_t>(sampler));
  if (const Sampler* s = slot.load(std::memory_order_acquire)) return *s;
  const FrameTexture& t = frame_.textures.at(static_cast<size_t>(texture));
  const TextureDescriptor& d = frame_.regs.textures.at(static_cast<size_t>(texture));
  const SamplerDescriptor& s = frame_.regs.samplers.at(static_cast<size_t>(sampler));
  const bool wants_coefficients = s.mode.base == BaseFilter::Cubic && s.kernel == kBsplineInterp;
  if (wants_coefficients != (d.content == TextureContent::BsplineCoefficients))
    throw InputError(fmt::format("texture {} ({}) holds {} but sampler {} is {} {}", texture, t.name,
                                 d.content == TextureContent::BsplineCoefficients ? "B-spline coefficients" : "texels",
                                 sampler, filter_mode_name(s.mode), s.kernel));
  auto smp = std::make_unique<Sampler>(*t.texels, s);
  if (wants_coefficients && (smp->cubic_normalize().scale_q != d.coeff_scale_q || smp->cubic_normalize().bias_q != d.coeff_bias_q))
    throw CheckFailed(fmt::format("texture {}: the golden prefilter's S, B differ from the descriptor's", texture));
  owned_.push_back(std::move(smp));
  slot.store(owned_.back().get(), std::memory_order_release);
  return *owned_.back();
}

int32_t GoldenUnit::lambda(const Trace& trace, size_t i) const {
  const size_t first = trace.mode == TraceMode::Quad ? i - i % 4 : i;
  const TextureDescriptor& d = frame_.regs.textures.at(trace.requests[first].texture);
  return request_lambda(trace, first, d.width, d.height);
}

AnisoLod GoldenUnit::lod(const Trace& trace, size_t i) const {
  const size_t first = trace.mode == TraceMode::Quad ? i - i % 4 : i;
  const TraceRequest& r = trace.requests[first];
  const SamplerDescriptor& s = frame_.regs.samplers.at(r.sampler);
  const TextureDescriptor& d = frame_.regs.textures.at(r.texture);
  if (!s.anisotropic()) return isotropic_lod(request_lambda(trace, first, d.width, d.height));
  return request_lod(trace, first, d.width, d.height, s.aniso());
}

std::vector<int32_t> GoldenUnit::lambdas(const Trace& trace) const {
  return trace_lambdas(trace, [this](int t) {
    const TextureDescriptor& d = frame_.regs.textures.at(static_cast<size_t>(t));
    return std::pair{d.width, d.height};
  });
}

}  // namespace tfu
