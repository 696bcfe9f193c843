// Exact 16-bit lerp with one final rounding: the vertical lerp of the bilinear lerp unit (GL 4.6
// Sec. 8.14.2; cmodel/datapath.hpp dp::bilinear_lerp) and the trilinear blend on Q.8 level results
// (tfu_level_blend, dp::level_blend). Combinational.
//
// Ports:
//   a, b [15:0] exact horizontal lerps (tfu_lerp_h) or Q.8 level results, 0..65280
//   f    [7:0]  weight of b, Q.8
//   c    [7:0]  (a (256 - f) + b f + 2^15) >> 16, rounding half up
//
// Because (c00 (256-fu) + c10 fu)(256-fv) + (c01 (256-fu) + c11 fu) fv is exactly sum c w with
// w = (256-fu|fu)(256-fv|fv), tfu_lerp_h followed by this block is bit-exact with dp::bilinear_lerp.
// Structure: tfu_lerp_v_diff (d = b - a), tfu_lerp_v_sum (the product and the sum, to 8 fraction
// bits), tfu_level_round (half up); the latency-4 bilinear top puts a register after the difference.
module tfu_lerp_v_round (
  input  logic [15:0] a,
  input  logic [15:0] b,
  input  logic [7:0]  f,
  output logic [7:0]  c
);
  logic [16:0] d;  // b - a, signed
  logic [15:0] q;  // Q.8
  tfu_lerp_v_diff u_diff (.a(a), .b(b), .d(d));
  tfu_lerp_v_sum u_sum (.a(a), .d(d), .f(f), .q(q));
  tfu_level_round u_round (.q(q), .c(c));
endmodule
