// lod_unit: lambda per pixel (Pharr, GPU Gems ch. 25; GL 4.6 Eq. 8.4-8.6) from the quad's coarse
// derivatives, the explicit LOD (textureLod) or the explicit gradients (textureGrad), through the
// log2 ROM of cmodel/lod.hpp, in texels of the request's texture (level-0 width and height from
// its texture descriptor); then the pixels one per cycle.
//
// Ports:
//   in  quad       QuadReq                 valid/ready
//   out pixel      PixelReq, lambda[15:0]  Q.8 before bias and clamp; one per cycle
//   in  registers  texture descriptors (width_m1, height_m1), sampler descriptors (mip_mode)
// A sampler without MIP-mapping has no level to select (GL: level 0), so its lambda is not used:
// the model then leaves it at 0 instead of evaluating the derivatives and the log2 ROM (software
// speed only; the pixels' timing is the same).
#pragma once

#include "cmodel/descriptors.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/trace.hpp"
#include "rtl/unit_ports.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

class LodUnit : public sim::Module {
 public:
  LodUnit(sim::Simulator& s, sim::Channel<QuadReq>& i, sim::Channel<PixelReq>& o, TraceMode mode, const Registers& regs)
      : Module(s, "lod_unit"), in_(i), out_(o), mode_(mode), regs_(regs) {}
  void evaluate() override {
    if (!holding_ && in_.can_pop()) {
      quad_ = in_.front();
      in_.pop();
      if (regs_.samplers[quad_.req.sampler].mode.mip == MipMode::None) {
        lambda_ = 0;
      } else {
        const TextureDescriptor& tex = regs_.textures[quad_.req.texture];
        switch (mode_) {
          case TraceMode::Quad: lambda_ = lambda_from_quad(quad_.s.data(), quad_.t.data(), tex.width, tex.height); break;
          case TraceMode::Lod: lambda_ = lambda_explicit(quad_.lod); break;
          case TraceMode::Grad:
            lambda_ = lambda_from_gradients(quad_.dsdx, quad_.dtdx, quad_.dsdy, quad_.dtdy, tex.width, tex.height);
            break;
        }
      }
      holding_ = true;
      k_ = 0;
      sim_.progress();
    }
    if (holding_ && out_.can_push()) {
      const auto k = static_cast<size_t>(k_);
      out_.push_slot() = {quad_.id + static_cast<uint32_t>(k_), quad_.req, quad_.s[k], quad_.t[k], lambda_};
      if (++k_ == quad_.npix) holding_ = false;
      sim_.progress();
    }
  }
  std::string state() const override { return fmt::format("{}, {}, holding {}", in_.state(), out_.state(), holding_); }
  bool busy() const { return holding_; }

 private:
  sim::Channel<QuadReq>& in_;
  sim::Channel<PixelReq>& out_;
  TraceMode mode_;
  const Registers& regs_;
  bool holding_ = false;
  QuadReq quad_;
  int32_t lambda_ = 0;
  int k_ = 0;
};

}  // namespace tfu::rtl
