// Rounding of a Q.8 channel to its code, half up (cmodel/datapath.hpp dp::round_level):
// c = (q + 2^7) >> 8. After tfu_lerp_v_sum it gives (sum + 2^15) >> 16 of the whole Q.16 sum:
// floor((floor(S / 2^8) + 2^7) / 2^8) = floor((S + 2^15) / 2^16). Combinational.
//
// Ports:
//   q [15:0]  Q.8 channel, 0..65407 (no carry out of 16 bits; tfu_lerp_v_sum gives <= 65280)
//   c [7:0]   (q + 128) >> 8
module tfu_level_round (
  input  logic [15:0] q,
  output logic [7:0]  c
);
  assign c = 8'((q + 16'd128) >> 8);
endmodule
