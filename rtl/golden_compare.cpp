#include "rtl/golden_compare.hpp"

#include <fmt/format.h>

#include "cmodel/fast_paths.hpp"

namespace tfu::rtl {

namespace {

// The plain golden datapath of one request, whatever dispatch the sampler was built with:
// Sampler::sample's plain targets (sample_plain, aniso_plain) spelled with the public calls.
Rgba8 plain_sample(const Sampler& smp, float s, float t, const AnisoLod& lod) {
  const Texel4 c = lod.probes == 1 ? smp.sample_channels(s, t, lod.lambda_q8) : smp.sample_channels(s, t, lod);
  return encode_texel(c, smp.texture().format);
}

}  // namespace

std::vector<Rgba8> golden_outputs(const GoldenUnit& golden, const Trace& trace, const UnitOutput& out) {
  std::vector<Rgba8> want(trace.requests.size());
  const Registers& regs = golden.frame().regs;
  const bool fast = fast_paths_enabled();
  AnisoLod lod;
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const TraceRequest& r = trace.requests[i];
    if (trace.mode != TraceMode::Quad || i % 4 == 0) lod = golden.lod(trace, i);
    const SamplerDescriptor& s = regs.samplers[r.sampler];
    const Sampler& smp = golden.sampler(r.texture, r.sampler);
    if (s.mode.base == BaseFilter::EdgePreserving && s.edge_shape == EdgeShape::CacheAware)
      want[i] = smp.sample_edge_masks(r.s, r.t, lod, out.edge_shapes.at(i).data());
    else
      want[i] = fast ? smp.sample(r.s, r.t, lod) : plain_sample(smp, r.s, r.t, lod);
  }
  return want;
}

std::string first_mismatch(const Trace& trace, const std::vector<Rgba8>& want, const UnitOutput& out, const std::string& where,
                           size_t first) {
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const Rgba8 have = out.pixels[i];
    if (want[i] == have) continue;
    const TraceRequest& r = trace.requests[i];
    return fmt::format("{}{}request {} (texture {}, sampler {}, s={:.9g}, t={:.9g}) at cycle {}: cycle model {},{},{},{} vs golden {},{},{},{}",
                       where, where.empty() ? "" : " ", first + i, r.texture, int{r.sampler}, r.s, r.t, out.response_cycle[i], have.r,
                       have.g, have.b, have.a, want[i].r, want[i].g, want[i].b, want[i].a);
  }
  return {};
}

}  // namespace tfu::rtl
