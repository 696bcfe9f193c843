// Exact 8-bit lerp of the bilinear lerp unit, its horizontal lerps (GL 4.6 Sec. 8.14.2;
// cmodel/datapath.hpp dp::bilinear_lerp). Combinational, no rounding.
//
// Ports:
//   a, b [7:0]  operands (unorm8 channel codes)
//   f    [7:0]  weight of b, Q.8 (0..255)
//   h   [15:0]  a (256 - f) + b f = 256 a + f (b - a), in 0..255*256 (a Q.8 channel); one 9 x 9-bit
//               signed multiplier
module tfu_lerp_h (
  input  logic [7:0]  a,
  input  logic [7:0]  b,
  input  logic [7:0]  f,
  output logic [15:0] h
);
  logic signed [8:0]  d;   // b - a, -255..255
  logic signed [17:0] p;   // f (b - a)
  assign d = $signed({1'b0, b}) - $signed({1'b0, a});
  assign p = 18'(d * $signed({1'b0, f}));
  assign h = 16'($signed({2'b00, a, 8'b0}) + p);  // 256 a + f (b - a), 0..65280
endmodule
