// Difference of the two horizontal lerps, the first part of the vertical lerp (tfu_lerp_v_round).
// Combinational.
//
// Ports:
//   a, b [15:0]  exact horizontal lerps (tfu_lerp_h, Q.8 channels)
//   d    [16:0]  b - a, signed, -65280..65280
module tfu_lerp_v_diff (
  input  logic [15:0] a,
  input  logic [15:0] b,
  output logic [16:0] d
);
  assign d = $signed({1'b0, b}) - $signed({1'b0, a});
endmodule
