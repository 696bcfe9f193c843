// kernel_select: the kernel-shape selector of the edge-preserving filter (Lee & Jen Sec. 3, Fig. 4).
// Textures are stored in BxB blocks, one per cache line; the kernel uses the texels of the blocks
// that the 2x2 bilinear footprint already touches: the cross inside a block, a T on a block edge,
// an L at a block corner. Policies:
//   static       shape = lee_jen::cache_block_mask(centre square, B)
//   cache-aware  static, plus every arm whose lines are resident in the cache when the footprint
//                reaches it (resolved by the tag probe of the texel_cache stage: `optional`)
//   full-cross   always the 12 texels (fetches whatever lines they need)
// Other filters pass through unchanged.
//
// Ports:
//   in  footprint  FootprintReq                            valid/ready
//   out footprint  FootprintReq + shape[11:0], optional[11:0]
#pragma once

#include "cmodel/edge_filter.hpp"
#include "rtl/unit_ports.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

enum class ShapePolicy { Static, CacheAware, FullCross };
const char* shape_policy_name(ShapePolicy p);
ShapePolicy shape_policy_from_name(const std::string& name);  // throws InputError

class KernelSelect : public sim::Module {
 public:
  KernelSelect(sim::Simulator& s, sim::Channel<FootprintReq>& i, sim::Channel<FootprintReq>& o, bool edge,
               ShapePolicy p, int block)
      : Module(s, "kernel_select"), in_(i), out_(o), edge_(edge), policy_(p), block_(block) {}
  // Combinational part: the shape (and optional arms) of an edge cross footprint.
  static void select(FootprintReq& f, ShapePolicy policy, int block) {
    f.tag.shape = lee_jen::kAllTexels;
    f.optional = 0;
    if (policy == ShapePolicy::FullCross) return;
    // The centre square's columns and rows of the cross's grid (cmodel/lee_jen_geometry.hpp).
    f.tag.shape = lee_jen::cache_block_mask_of_grid(f.grid.x, f.grid.y, block);
    if (policy == ShapePolicy::CacheAware) f.optional = static_cast<lee_jen::TexelMask>(lee_jen::kAllTexels & ~f.tag.shape);
  }
  void evaluate() override {
    if (!in_.can_pop() || !out_.can_push()) return;
    FootprintReq& f = out_.push_slot();
    f = in_.front();
    in_.pop();
    if (edge_) select(f, policy_, block_);
    sim_.progress();
  }
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }

 private:
  sim::Channel<FootprintReq>& in_;
  sim::Channel<FootprintReq>& out_;
  bool edge_;
  ShapePolicy policy_;
  int block_;
};

}  // namespace tfu::rtl
