// The filter datapaths' pipeline depths (unit configuration `filter.edge_stages`,
// `filter.bilinear_stages`): the depths the SystemVerilog tops offer, and the depths of the model's
// own blocks, defined once (the field table of rtl/unit_config.cpp, the pipeline registers of
// rtl/pipeline_registers.hpp and the check of the SV tops' parameters, testbench/test_datapath_depth.cpp,
// read them). How a depth maps onto the blocks: rtl/pipeline_registers.hpp, docs/cycle-model.md
// ("Datapath depth").
#pragma once

#include <array>

namespace tfu::rtl {

// A pipeline depth the SV offers: the top's latency in clocks and its module.
struct OfferedDepth {
  int clocks;
  const char* sv_top;
};
// The edge-preserving interpolator: Lee & Jen's 3 clocks (CUTS 8'b0010_0010) and the 8-clock top
// that meets 101.2 MHz in OSU 0.35 um (CUTS 8'b1101_1111; docs/silicon.md, "Lee & Jen on equal
// terms"). The model's three edge blocks are the first.
inline constexpr std::array<OfferedDepth, 2> kEdgeDepths{{{3, "tfu_edge_interp_top"}, {8, "tfu_edge_interp_top_l8"}}};
inline constexpr int kEdgeBlockClocks = 3;  // edge_median, edge_direction, edge_merge
static_assert(kEdgeDepths[0].clocks == kEdgeBlockClocks, "the model's edge blocks are the 3-clock top's stages");
// The bilinear baseline: CUT_V 0 (3 clocks) and 1 (4 clocks, 101.2 MHz in OSU 0.35 um).
inline constexpr std::array<OfferedDepth, 2> kBilinearDepths{{{3, "tfu_bilinear_top"}, {4, "tfu_bilinear_top_l4"}}};
// The filter block's depth counted as the bilinear top's: its input register (the texel cache's
// output register) and one clock for both lerps, the blend and the encode.
inline constexpr int kFilterBlockDepth = 2;

}  // namespace tfu::rtl
