// The vertical lerp with its one final rounding, from a and d = b - a (tfu_lerp_v_diff); the second
// part of tfu_lerp_v_round. Combinational.
//
// Ports:
//   a [15:0]  exact horizontal lerp (tfu_lerp_h)
//   d [16:0]  b - a, signed
//   f [7:0]   weight of b, Q.8
//   c [7:0]   (256 a + f d + 2^15) >> 16 = (a (256 - f) + b f + 2^15) >> 16, rounding half up
module tfu_lerp_v_sum (
  input  logic [15:0] a,
  input  logic [16:0] d,
  input  logic [7:0]  f,
  output logic [7:0]  c
);
  logic signed [25:0] p;   // f (b - a)
  logic signed [25:0] s;   // 256 a + f (b - a) + 2^15, 0..255*65536 + 2^15 < 2^24
  assign p = 26'($signed(d) * $signed({1'b0, f}));
  assign s = $signed({2'b00, a, 8'b0}) + p + 26'sd32768;
  assign c = 8'(s >>> 16);
endmodule
