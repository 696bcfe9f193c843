// The vertical lerp's exact sum, kept to 8 fraction bits, from a and d = b - a (tfu_lerp_v_diff);
// the second part of tfu_lerp_v_round. Combinational, no rounding.
//
// Ports:
//   a [15:0]  exact horizontal lerp (tfu_lerp_h), or a Q.8 level result (tfu_level_blend)
//   d [16:0]  b - a, signed
//   f [7:0]   weight of b, Q.8
//   q [15:0]  (256 a + f d) >> 8 = (a (256 - f) + b f) >> 8: the Q.16 sum's bits 23..8, a Q.8 channel
//             (cmodel/datapath.hpp dp::bilinear_lerp_q8; kLevelFracBits = 8), 0..65280 for a, b in
//             0..65280
module tfu_lerp_v_sum (
  input  logic [15:0] a,
  input  logic [16:0] d,
  input  logic [7:0]  f,
  output logic [15:0] q
);
  logic signed [25:0] p;   // f (b - a)
  logic signed [25:0] s;   // 256 a + f (b - a), 0..255*65536 < 2^24
  assign p = 26'($signed(d) * $signed({1'b0, f}));
  assign s = $signed({2'b00, a, 8'b0}) + p;
  assign q = 16'(s >>> 8);
endmodule
