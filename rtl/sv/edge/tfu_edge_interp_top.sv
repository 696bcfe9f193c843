// Edge-preserving interpolator of Lee & Jen 2003 (Sec. 2.2, 2.3, 3, 6), fully pipelined, RGBA8;
// bit-exact with lee_jen::edge_preserving_interpolate (cmodel/edge_filter.cpp) for the nine kernel
// shapes (cross, T0..T3, L0..L3). VS16X2 is not in the SV (docs/sv-edge.md).
//
// Parameter:
//   CUTS [7:0]  pipeline cut points: bit k = a register after step k below (the output register
//               after step 8 is always there). Latency LATENCY = 1 + popcount(CUTS) clocks: a
//               request on the inputs at rising edge n is on out_valid / c after edge
//               n + LATENCY - 1. Offered and tested (docs/sv-edge.md):
//                 8'b0010_0010  latency 3 (Lee & Jen Sec. 6: "3-clock latency"; the default)
//                 8'b1101_1111  latency 8 (meets 101.2 MHz in OSU 0.35 um, docs/silicon.md;
//                               wrapper tfu_edge_interp_top_l8)
//
// Ports:
//   clk, rst_n        rising-edge clock; synchronous active-low reset (clears the valid bits only)
//   in_valid          a request on texels, shape, fu, fv
//   texels [383:0]    C1..C12 (RGBA8, R in the low byte), Cn at bits [32(n-1) +: 32]; texels missing
//                     from `shape` are never used
//   shape  [11:0]     available texels, bit n-1 = Cn (one of the nine kernel shapes)
//   fu, fv [7:0]      fractions of the sample point in the centre square C4 C5 C8 C9, Q.8
//   out_valid, c [31:0]  the interpolated texel, registered
// One request per clock, no backpressure. Inputs feed step 0's logic directly (the texels arrive
// from the texel cache's registers).
//
// Steps (what is live after each step is what its cut registers):
//   0  12 x RGB->Y (carry-save adder trees), keys Y * 16 + n      -> texels, shape, fu, fv, keys
//   1  the 40-cell median network with its T/L input select       -> texels, shape, fu, fv, low[1..12]
//   2  low-pass texel select (Cn_low); 22 x |dR| + |dG| + |dB|; the 22 weight ROMs; H_n = C_n - Cn_low
//                                                                  -> dp, w, shape, Cn_low, H, fu, fv
//   3  22 x (w * dP, usable); Eq. 5 horizontal lerps               -> leaves, hx0, hx1, Cn_low, fu, fv
//   4  min tree levels 1-3 (32 -> 4); Eq. 5 dy = hx1 - hx0        -> 4 nodes, hx0, dy, Cn_low, fu, fv
//   5  min tree levels 4-5 (-> direction); Eq. 5 vertical lerp    -> direction, C_high, Cn_low, fu, fv
//   6  endpoint select of the direction (22:1), its t             -> Cp_low, Cq_low, t, C_high
//   7  Eq. 3 lerp                                                  -> C_low, C_high
//   8  Eq. 6 sum and clamp (4 channels)                            -> c (output register)
// With the default cuts (after 1 and 5) the three stages are Lee & Jen's: medians; direction
// select (with the high-frequency part beside it); merge.
module tfu_edge_interp_top #(
  parameter logic [7:0] CUTS = 8'b0010_0010
) (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         in_valid,
  input  logic [383:0] texels,
  input  logic [11:0]  shape,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic         out_valid,
  output logic [31:0]  c
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam int E = 24;  // node of the min tree: {usable, cost[17:0], index[4:0]} (tfu_edge_min_level)

  // ---------------- step 0: RGB->Y, keys ----------------
  logic [191:0] key;
  for (genvar n = 0; n < 12; n++) begin : g_key
    logic [11:0] y;
    tfu_edge_rgb_to_y u_y (.r(texels[32*n +: 8]), .g(texels[32*n + 8 +: 8]), .b(texels[32*n + 16 +: 8]), .y(y));
    assign key[16*n +: 16] = {y, 4'(n + 1)};
  end
  logic         v0;
  logic [383:0] texels_0;
  logic [11:0]  shape_0;
  logic [7:0]   fu_0, fv_0;
  logic [191:0] key_0;
  tfu_pipe_reg #(.W(384 + 12 + 16 + 192), .REG(CUTS[0])) u_cut0 (
      .clk(clk), .rst_n(rst_n), .vin(in_valid), .d({texels, shape, fu, fv, key}), .vout(v0),
      .q({texels_0, shape_0, fu_0, fv_0, key_0}));

  // ---------------- step 1: medians ----------------
  logic [47:0] low;
  tfu_median_network u_median (.key(key_0), .shape(shape_0), .low(low));
  logic         v1;
  logic [383:0] texels_1;
  logic [11:0]  shape_1;
  logic [7:0]   fu_1, fv_1;
  logic [47:0]  low_1;
  tfu_pipe_reg #(.W(384 + 12 + 16 + 48), .REG(CUTS[1])) u_cut1 (
      .clk(clk), .rst_n(rst_n), .vin(v0), .d({texels_0, shape_0, fu_0, fv_0, low}), .vout(v1),
      .q({texels_1, shape_1, fu_1, fv_1, low_1}));

  // ---------------- step 2: low-pass texels, colour differences, ROMs, H_n ----------------
  logic [383:0] lowtex;
  tfu_edge_lowpass_select u_lowsel (.texels(texels_1), .low(low_1), .lowtex(lowtex));
  logic [287:0] lowrgb;
  for (genvar n = 0; n < 12; n++) begin : g_rgb
    assign lowrgb[24*n +: 24] = lowtex[32*n +: 24];
  end
  logic [10*NDIR-1:0] dp;
  logic [8*NDIR-1:0]  w;
  tfu_edge_dir_dp u_dp (.lowrgb(lowrgb), .dp(dp));
  tfu_edge_dir_roms u_roms (.fu(fu_1[7:4]), .fv(fv_1[7:4]), .w(w));
  logic [127:0] centre, lowc;  // the centre square (tfu_edge_pkg::CENTRE) in the order of Eq. 5's weights
  for (genvar k = 0; k < 4; k++) begin : g_centre
    localparam int N = 32'(tfu_edge_pkg::CENTRE[4*k +: 4]) - 1;
    assign centre[32*k +: 32] = texels_1[32*N +: 32];
    assign lowc[32*k +: 32] = lowtex[32*N +: 32];
  end
  logic [143:0] h;
  tfu_edge_high_diff u_hdiff (.centre(centre), .lowc(lowc), .h(h));
  logic               v2;
  logic [10*NDIR-1:0] dp_2;
  logic [8*NDIR-1:0]  w_2;
  logic [11:0]        shape_2;
  logic [383:0]       lowtex_2;
  logic [143:0]       h_2;
  logic [7:0]         fu_2, fv_2;
  tfu_pipe_reg #(.W(10*NDIR + 8*NDIR + 12 + 384 + 144 + 16), .REG(CUTS[2])) u_cut2 (
      .clk(clk), .rst_n(rst_n), .vin(v1), .d({dp, w, shape_1, lowtex, h, fu_1, fv_1}), .vout(v2),
      .q({dp_2, w_2, shape_2, lowtex_2, h_2, fu_2, fv_2}));

  // ---------------- step 3: weighted costs; Eq. 5 horizontal lerps ----------------
  logic [32*E-1:0] leaf;
  tfu_edge_dir_leaves u_leaves (.dp(dp_2), .w(w_2), .shape(shape_2), .leaf(leaf));
  logic [75:0] hx0, hx1;
  tfu_edge_high_x u_hx (.h(h_2), .fu(fu_2), .hx0(hx0), .hx1(hx1));
  logic            v3;
  logic [32*E-1:0] leaf_3;
  logic [75:0]     hx0_3, hx1_3;
  logic [383:0]    lowtex_3;
  logic [7:0]      fu_3, fv_3;
  tfu_pipe_reg #(.W(32*E + 76 + 76 + 384 + 16), .REG(CUTS[3])) u_cut3 (
      .clk(clk), .rst_n(rst_n), .vin(v2), .d({leaf, hx0, hx1, lowtex_2, fu_2, fv_2}), .vout(v3),
      .q({leaf_3, hx0_3, hx1_3, lowtex_3, fu_3, fv_3}));

  // ---------------- step 4: min tree levels 1-3; Eq. 5 dy ----------------
  logic [16*E-1:0] l1;
  logic [8*E-1:0]  l2;
  logic [4*E-1:0]  l3;
  tfu_edge_min_level #(.N(32)) u_l1 (.in(leaf_3), .out(l1));
  tfu_edge_min_level #(.N(16)) u_l2 (.in(l1), .out(l2));
  tfu_edge_min_level #(.N(8)) u_l3 (.in(l2), .out(l3));
  logic [79:0] dy;
  tfu_edge_high_dy u_hdy (.hx0(hx0_3), .hx1(hx1_3), .dy(dy));
  logic           v4;
  logic [4*E-1:0] l3_4;
  logic [75:0]    hx0_4;
  logic [79:0]    dy_4;
  logic [383:0]   lowtex_4;
  logic [7:0]     fu_4, fv_4;
  tfu_pipe_reg #(.W(4*E + 76 + 80 + 384 + 16), .REG(CUTS[4])) u_cut4 (
      .clk(clk), .rst_n(rst_n), .vin(v3), .d({l3, hx0_3, dy, lowtex_3, fu_3, fv_3}), .vout(v4),
      .q({l3_4, hx0_4, dy_4, lowtex_4, fu_4, fv_4}));

  // ---------------- step 5: min tree levels 4-5, direction; Eq. 5 vertical lerp ----------------
  logic [2*E-1:0] l4;
  logic [E-1:0]   root;
  tfu_edge_min_level #(.N(4)) u_l4 (.in(l3_4), .out(l4));
  tfu_edge_min_level #(.N(2)) u_l5 (.in(l4), .out(root));
  logic [4:0] dir;
  assign dir = root[E-1] ? root[4:0] : 5'd0;  // no usable direction: 0, as tfu_edge_dir_select
  logic [39:0] chigh;
  tfu_edge_high_y u_hy (.hx0(hx0_4), .dy(dy_4), .fv(fv_4), .chigh(chigh));
  logic         v5;
  logic [4:0]   dir_5;
  logic [39:0]  chigh_5;
  logic [383:0] lowtex_5;
  logic [7:0]   fu_5, fv_5;
  tfu_pipe_reg #(.W(5 + 40 + 384 + 16), .REG(CUTS[5])) u_cut5 (
      .clk(clk), .rst_n(rst_n), .vin(v4), .d({dir, chigh, lowtex_4, fu_4, fv_4}), .vout(v5),
      .q({dir_5, chigh_5, lowtex_5, fu_5, fv_5}));

  // ---------------- step 6: endpoints of the direction ----------------
  logic [31:0] cp, cq;
  logic [7:0]  t;
  tfu_edge_endpoints u_ends (.lowtex(lowtex_5), .dir(dir_5), .fu(fu_5), .fv(fv_5), .cp(cp), .cq(cq), .t(t));
  logic        v6;
  logic [31:0] cp_6, cq_6;
  logic [7:0]  t_6;
  logic [39:0] chigh_6;
  tfu_pipe_reg #(.W(32 + 32 + 8 + 40), .REG(CUTS[6])) u_cut6 (
      .clk(clk), .rst_n(rst_n), .vin(v5), .d({cp, cq, t, chigh_5}), .vout(v6), .q({cp_6, cq_6, t_6, chigh_6}));

  // ---------------- step 7: Eq. 3 ----------------
  logic [31:0] clow;
  tfu_edge_low_lerp u_low (.cp(cp_6), .cq(cq_6), .t(t_6), .clow(clow));
  logic        v7;
  logic [31:0] clow_7;
  logic [39:0] chigh_7;
  tfu_pipe_reg #(.W(32 + 40), .REG(CUTS[7])) u_cut7 (
      .clk(clk), .rst_n(rst_n), .vin(v6), .d({clow, chigh_6}), .vout(v7), .q({clow_7, chigh_7}));

  // ---------------- step 8: Eq. 6, output register ----------------
  logic [31:0] merged;
  tfu_edge_sum_clamp u_sum (.clow(clow_7), .chigh(chigh_7), .c(merged));
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else out_valid <= v7;
    c <= merged;
  end
endmodule
