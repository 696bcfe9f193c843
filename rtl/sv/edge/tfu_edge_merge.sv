// Merge of the edge-preserving filter (Lee & Jen 2003 Eq. 3, 5, 6), RGBA8; bit-exact with
// lee_jen::edge_merge (cmodel/edge_filter.cpp). Per channel (alpha included):
//   C_low  = ((256 - t) Cp_low + t Cq_low + 128) >> 8          t = fu or fv of direction `dir` (Eq. 3)
//          = (256 Cp_low + t (Cq_low - Cp_low) + 128) >> 8     (one signed 8 x 9 multiplier)
//   H_n    = C_n - Cn_low, n = 4, 5, 8, 9                      9 bits signed
//   C_high = (sum H_n w_n + 2^15) >> 16 (floor), w_n the bilinear weights (256 - fu | fu)(256 - fv | fv)
//            computed exactly as two lerps: h0 = 256 H4 + fu (H5 - H4), h1 = 256 H8 + fu (H9 - H8),
//            sum = 256 h0 + fv (h1 - h0)   (Eq. 5; no rounding before the last shift)
//   I      = clamp(C_low + C_high, 0, 255)                    (Eq. 6)
// Endpoints and blend axis of each direction: package tfu_edge_pkg (gen/tfu_edge_pkg.sv).
//
// Ports:
//   lowtex [383:0]  Cn_low (RGBA) at bits [32(n-1) +: 32], R in the low byte
//   centre [127:0]  C4, C5, C8, C9 (RGBA) at bits [0 +: 32], [32 +: 32], [64 +: 32], [96 +: 32]
//   dir    [4:0]    chosen direction, 0..21 (tfu_edge_dir_select)
//   fu, fv [7:0]    fractions of the sample point in the centre square, Q.8
//   c      [31:0]   interpolated texel
// Structure: tfu_edge_endpoints and tfu_edge_low_lerp (Eq. 3); tfu_edge_high_diff, tfu_edge_high_x,
// tfu_edge_high_dy and tfu_edge_high_y (Eq. 5); tfu_edge_sum_clamp (Eq. 6). The pipelined top
// (tfu_edge_interp_top) uses the same parts with registers between them. Combinational.
module tfu_edge_merge (
  input  logic [383:0] lowtex,
  input  logic [127:0] centre,
  input  logic [4:0]   dir,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic [31:0]  c
);
  logic [31:0]  cp, cq, clow;
  logic [7:0]   t;
  logic [143:0] h;
  logic [75:0]  hx0, hx1;
  logic [79:0]  dy;
  logic [39:0]  chigh;
  tfu_edge_endpoints u_ends (.lowtex(lowtex), .dir(dir), .fu(fu), .fv(fv), .cp(cp), .cq(cq), .t(t));
  tfu_edge_low_lerp u_low (.cp(cp), .cq(cq), .t(t), .clow(clow));
  tfu_edge_high_diff u_hdiff (.centre(centre), .lowc({lowtex[32*8 +: 32], lowtex[32*7 +: 32], lowtex[32*4 +: 32], lowtex[32*3 +: 32]}),
                              .h(h));
  tfu_edge_high_x u_hx (.h(h), .fu(fu), .hx0(hx0), .hx1(hx1));
  tfu_edge_high_dy u_hdy (.hx0(hx0), .hx1(hx1), .dy(dy));
  tfu_edge_high_y u_hy (.hx0(hx0), .dy(dy), .fv(fv), .chigh(chigh));
  tfu_edge_sum_clamp u_sum (.clow(clow), .chigh(chigh), .c(c));
endmodule
