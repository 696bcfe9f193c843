// Exact 16-bit lerp with one final rounding: the vertical lerp of the bilinear lerp unit (GL 4.6
// Sec. 8.14.2; cmodel/datapath.hpp dp::bilinear_lerp). Combinational.
//
// Ports:
//   a, b [15:0] exact horizontal lerps (tfu_lerp_h, Q.8 channels)
//   f    [7:0]  weight of b, Q.8
//   c    [7:0]  (a (256 - f) + b f + 2^15) >> 16, rounding half up
//
// Because (c00 (256-fu) + c10 fu)(256-fv) + (c01 (256-fu) + c11 fu) fv is exactly sum c w with
// w = (256-fu|fu)(256-fv|fv), tfu_lerp_h followed by this block is bit-exact with dp::bilinear_lerp.
module tfu_lerp_v_round (
  input  logic [15:0] a,
  input  logic [15:0] b,
  input  logic [7:0]  f,
  output logic [7:0]  c
);
  logic signed [16:0] d;   // b - a, -65280..65280
  logic signed [25:0] p;   // f (b - a)
  logic signed [25:0] s;   // 256 a + f (b - a) + 2^15, 0..255*65536 + 2^15 < 2^24
  assign d = $signed({1'b0, b}) - $signed({1'b0, a});
  assign p = 26'(d * $signed({1'b0, f}));
  assign s = $signed({2'b00, a, 8'b0}) + p + 26'sd32768;
  assign c = 8'(s >>> 16);
endmodule
