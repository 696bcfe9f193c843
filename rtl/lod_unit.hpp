// lod_unit: lambda per pixel (Pharr, GPU Gems ch. 25; GL 4.6 Eq. 8.4-8.6) from the quad's coarse
// derivatives, the explicit LOD (textureLod) or the explicit gradients (textureGrad), through the
// log2 ROM of cmodel/lod.hpp, in texels of the request's texture (level-0 width and height from
// its texture descriptor); then the pixels one per cycle. For an anisotropic sampler (max_aniso > 1
// on a MIP-mapped mode) the anisotropic LOD unit of cmodel/aniso.hpp (EXT_texture_filter_anisotropic:
// axis lengths along the screen axes or the footprint ellipse's axes, probe count N by exact
// compares, lambda = log2(Pmax / N)) on the same derivatives;
// the pixels carry N and the major derivative vector to the address generator.
//
// Ports:
//   in  quad       QuadReq                 valid/ready
//   out pixel      PixelReq: lambda[15:0] Q.8 before bias and clamp, probes[4:0], major_du[31:0],
//                  major_dv[31:0]; one per cycle
//   in  registers  texture descriptors (width_m1, height_m1), sampler descriptors (mip_mode,
//                  max_aniso_m1, aniso_rounding, aniso_threshold, aniso_axes)
// A sampler without MIP-mapping has no level to select (GL: level 0), so its lambda is not used:
// the model then leaves it at 0 instead of evaluating the derivatives and the log2 ROM (software
// speed only; the pixels' timing is the same). A lod trace has no derivatives: one probe (N = 1).
// An isotropic sampler takes the isotropic unit (lambda_from_quad / lambda_from_gradients), whose
// lambda equals aniso_lod's with max_aniso 1 bit for bit (tested in test_aniso).
#pragma once

#include "cmodel/aniso.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/trace.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class LodUnit : public sim::Module {
 public:
  LodUnit(sim::Simulator& s, sim::Channel<QuadReq>& i, sim::Channel<PixelReq>& o, TraceMode mode, const Registers& regs)
      : Module(s, "lod_unit"), in_(i), out_(o), mode_(mode), regs_(regs) {}
  void evaluate() override {
    if (!holding_ && in_.can_pop()) {
      quad_ = in_.front();
      in_.pop();
      lod_ = quad_lod(quad_);
      holding_ = true;
      k_ = 0;
      sim_.progress();
    }
    if (holding_ && out_.can_push()) {
      out_.push_slot() = pixel(quad_, lod_, k_);
      if (++k_ == quad_.npix) holding_ = false;
      sim_.progress();
    }
  }
  // The combinational parts: lambda and the anisotropic footprint of a quad (quad_lod below), and
  // its pixel k.
  static PixelReq pixel(const QuadReq& q, const AnisoLod& lod, int k) {
    const auto i = static_cast<size_t>(k);
    return {q.id + static_cast<uint32_t>(k), q.req, q.s[i], q.t[i], lod.lambda_q8, lod.probes, lod.major_du_q16, lod.major_dv_q16};
  }
  std::string state() const override { return fmt::format("{}, {}, holding {}", in_.state(), out_.state(), holding_); }
  bool busy() const { return holding_; }
  // The block's timing for the recurrence engine, beside evaluate(), which takes a quad when it
  // holds none and pushes its pixels one per cycle, the first in the cycle it took the quad: a
  // SequencerTiming (rtl/timing.hpp), quads in, pixels out. Both change together.
  SequencerTiming timing;

 private:
  sim::Channel<QuadReq>& in_;
  sim::Channel<PixelReq>& out_;
  TraceMode mode_;
  const Registers& regs_;
  bool holding_ = false;
  QuadReq quad_;
  AnisoLod lod_;
  int k_ = 0;

  // The texel-space derivatives of a quad or gradient request (the input stage); none in lod mode.
  TexelDerivatives derivatives(const QuadReq& q, const TextureDescriptor& tex) const {
    if (mode_ == TraceMode::Quad) return derivatives_from_quad(q.s.data(), q.t.data(), tex.width, tex.height);
    return derivatives_from_gradients(q.dsdx, q.dtdx, q.dsdy, q.dtdy, tex.width, tex.height);
  }

 public:
  // lambda and the anisotropic footprint of one quad (or pixel).
  AnisoLod quad_lod(const QuadReq& q) const {
    const SamplerDescriptor& smp = regs_.samplers[q.req.sampler];
    if (smp.mode.mip == MipMode::None) return isotropic_lod(0);
    if (mode_ == TraceMode::Lod) return isotropic_lod(lambda_explicit(q.lod));
    const TextureDescriptor& tex = regs_.textures[q.req.texture];
    if (smp.anisotropic()) return aniso_lod(derivatives(q, tex), smp.aniso());
    if (mode_ == TraceMode::Quad) return isotropic_lod(lambda_from_quad(q.s.data(), q.t.data(), tex.width, tex.height));
    return isotropic_lod(lambda_from_gradients(q.dsdx, q.dtdx, q.dsdy, q.dtdy, tex.width, tex.height));
  }
};

}  // namespace tfu::rtl
