// The golden model of the whole unit: requests that name a texture and a sampler descriptor, served
// by the golden sampler (sampler.hpp) over the frame's registers. Untimed; what the cycle model must
// equal bit for bit on every request.
//
//   lambda  the LOD unit of the request's texture (level-0 size from its descriptor), trace.hpp;
//   lod     with an anisotropic sampler also the probe count and major axis (aniso.hpp)
//   sample  the Sampler of (texture, sampler): built once per pair on first use (thread-safe)
// A bspline-interp request names the coefficient texture the driver made (FrameBuilder::bind); the
// golden sampler prefilters the source texels itself with the same function and must arrive at the
// descriptor's S and B registers (checked when the pair is built).
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include "cmodel/frame.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"

namespace tfu {

class GoldenUnit {
 public:
  explicit GoldenUnit(const Frame& frame)
      : frame_(frame), slots_(frame.regs.textures.size() * frame.regs.samplers.size()) {}
  const Frame& frame() const { return frame_; }
  const Sampler& sampler(int texture, int sampler) const {
    const Sampler* s = slots_[static_cast<size_t>(texture) * frame_.regs.samplers.size() + static_cast<size_t>(sampler)].load(
        std::memory_order_acquire);
    return s ? *s : build(texture, sampler);
  }
  // lambda of request i (quad mode: of its quad) before bias and clamp.
  int32_t lambda(const Trace& trace, size_t i) const;
  std::vector<int32_t> lambdas(const Trace& trace) const;
  // The LOD unit's whole result for request i (quad mode: of its quad) under its sampler: for an
  // anisotropic sampler (SamplerDescriptor::anisotropic()) request_lod with the sampler's fields,
  // else isotropic_lod(lambda(trace, i)) (the same lambda; one probe).
  AnisoLod lod(const Trace& trace, size_t i) const;
  Rgba8 sample(const TraceRequest& r, int32_t lambda_q8) const {
    return sampler(r.texture, r.sampler).sample(r.s, r.t, lambda_q8);
  }
  Rgba8 sample(const TraceRequest& r, const AnisoLod& lod) const { return sampler(r.texture, r.sampler).sample(r.s, r.t, lod); }

 private:
  const Frame& frame_;
  // One slot per (texture, sampler) pair, filled on first use under the mutex.
  mutable std::vector<std::atomic<const Sampler*>> slots_;
  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<Sampler>> owned_;
  const Sampler& build(int texture, int sampler) const;
};

}  // namespace tfu
