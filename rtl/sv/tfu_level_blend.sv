// Trilinear blend unit (GL 4.6 Sec. 8.14.3, *_MIPMAP_LINEAR; bit-exact with tfu::dp::level_blend of
// cmodel/datapath.hpp for 8-bit channels) on the two levels' Q.8 results, so that the filtered
// value is rounded once, here (docs/sampler.md, docs/number-formats.md). Combinational.
//
// Ports:
//   c0 [63:0]  Q.8 result of level floor(lambda)      channel k in bits [16k+15:16k], 0..65280
//              (tfu_bilinear_top's q; NEAREST, CUBIC, EDGE_PRESERVING codes enter as code << 8)
//   c1 [63:0]  Q.8 result of level floor(lambda) + 1
//   f   [7:0]  weight of level 1: lambda & 255 (Q.8)
//   c  [31:0]  per channel (c0 (256 - f) + c1 f + 2^15) >> 16, rounding half up
// Per channel the vertical lerp of the bilinear unit (tfu_lerp_v_round: a 17 x 9-bit product).
module tfu_level_blend (
  input  logic [63:0] c0,
  input  logic [63:0] c1,
  input  logic [7:0]  f,
  output logic [31:0] c
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    tfu_lerp_v_round u_v (.a(c0[16*ch +: 16]), .b(c1[16*ch +: 16]), .f(f), .c(c[8*ch +: 8]));
  end
endmodule
