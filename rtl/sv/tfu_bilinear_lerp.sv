// Bilinear lerp unit, 8-bit RGBA channels (GL 4.6 Sec. 8.14.2 Eq. 8.10-8.11; bit-exact with
// tfu::dp::bilinear_lerp of cmodel/datapath.hpp for rgba8 / l8 texels). Combinational.
//
// Ports:
//   c00 [31:0]  texel (i0, j0)          channel k (R, G, B, A = 0..3) in bits [8k+7:8k]
//   c10 [31:0]  texel (i0 + 1, j0)
//   c01 [31:0]  texel (i0, j0 + 1)
//   c11 [31:0]  texel (i0 + 1, j0 + 1)
//   fu, fv [7:0] subtexel fractions, Q.8 (u & 255, v & 255)
//   c   [31:0]  filtered colour: per channel (sum c w + 2^15) >> 16, w = (256-fu|fu)(256-fv|fv)
//
// Per channel: two exact horizontal lerps (tfu_lerp_h, 16 bits) and one vertical lerp with a
// single rounding (tfu_lerp_v_round); 3 signed multipliers (9x9, 9x9, 17x9) instead of four
// 8 x 17-bit products; identical sum, so bit-exact.
module tfu_bilinear_lerp (
  input  logic [31:0] c00,
  input  logic [31:0] c10,
  input  logic [31:0] c01,
  input  logic [31:0] c11,
  input  logic [7:0]  fu,
  input  logic [7:0]  fv,
  output logic [31:0] c
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic [15:0] h0, h1;
    tfu_lerp_h u_h0 (.a(c00[8*ch +: 8]), .b(c10[8*ch +: 8]), .f(fu), .h(h0));
    tfu_lerp_h u_h1 (.a(c01[8*ch +: 8]), .b(c11[8*ch +: 8]), .f(fu), .h(h1));
    tfu_lerp_v_round u_v (.a(h0), .b(h1), .f(fv), .c(c[8*ch +: 8]));
  end
endmodule
