// kernel_select: the kernel-shape selector of the edge-preserving filter (Lee & Jen Sec. 3, Fig. 4).
// A tiled texture is stored in tiles of one cache line; the kernel uses the texels of the tiles that
// the 2x2 bilinear footprint already touches: the cross inside a tile, a T on a tile edge, an L at
// a tile corner. The request's sampler descriptor chooses the policy (edge_shape):
//   static       shape = lee_jen::cache_block_mask(centre square, tile side)
//   cache-aware  static, plus every arm whose lines are resident in the cache when the footprint
//                reaches it (resolved by the tag probe of the texel_cache stage: `optional`)
//   cross        always the 12 texels (fetches whatever lines they need)
// A linear-layout texture has no tiles: static and cache-aware use the cross there. Other filters
// pass through unchanged.
//
// Ports:
//   in  footprint  FootprintReq                            valid/ready
//   out footprint  FootprintReq + shape[11:0], optional[11:0]
//   in  registers  sampler descriptor (edge_shape), texture descriptor (layout, tile_log2)
#pragma once

#include "cmodel/descriptors.hpp"
#include "cmodel/edge_filter.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

class KernelSelect : public sim::Module {
 public:
  KernelSelect(sim::Simulator& s, sim::Channel<FootprintReq>& i, sim::Channel<FootprintReq>& o, const Registers& regs)
      : Module(s, "kernel_select"), in_(i), out_(o), regs_(regs) {}
  // Combinational part: the shape (and optional arms) of an edge cross footprint under a policy and
  // the texture's tile side (0: no tiles).
  static void select(FootprintReq& f, EdgeShape policy, int tile) {
    f.tag.shape = lee_jen::kAllTexels;
    f.optional = 0;
    if (policy == EdgeShape::Cross || tile == 0) return;
    // The centre square's columns and rows of the cross's grid (cmodel/lee_jen_geometry.hpp).
    f.tag.shape = lee_jen::cache_block_mask_of_grid(f.grid.x, f.grid.y, tile);
    if (policy == EdgeShape::CacheAware) f.optional = static_cast<lee_jen::TexelMask>(lee_jen::kAllTexels & ~f.tag.shape);
  }
  void evaluate() override {
    if (!in_.can_pop() || !out_.can_push()) return;
    FootprintReq& f = out_.push_slot();
    f = in_.front();
    in_.pop();
    shape(f);
    sim_.progress();
  }
  // The block's combinational part: an edge footprint's shape from its descriptors (others pass).
  void shape(FootprintReq& f) const {
    if (f.tag.base != BaseFilter::EdgePreserving) return;
    const TextureDescriptor& t = regs_.textures[f.tag.req.texture];
    select(f, regs_.samplers[f.tag.req.sampler].edge_shape, t.layout == MemoryLayout::Tiled ? t.tile_side() : 0);
  }
  std::string state() const override { return fmt::format("{}, {}", in_.state(), out_.state()); }
  // The block's timing for the recurrence engine, beside evaluate(), which moves its input's head
  // when its output has room, one per cycle: an InOrderTiming (rtl/timing.hpp). Both change together.
  InOrderTiming timing;

 private:
  sim::Channel<FootprintReq>& in_;
  sim::Channel<FootprintReq>& out_;
  const Registers& regs_;
};

}  // namespace tfu::rtl
