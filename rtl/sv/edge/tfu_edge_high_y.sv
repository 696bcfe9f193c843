// Vertical lerp and rounding of the high-frequency part (Lee & Jen 2003 Eq. 5), per channel; part of
// tfu_edge_merge:
//   s      = 256 hx0 + fv dy + 2^15 = sum H_n w_n + 2^15 (bilinear Q.16 weights, no earlier rounding)
//   C_high = s >>> 16   (floor; 10 bits signed, -255..255)
//
// Ports:
//   hx0   [75:0]  channel ch at bits [19ch +: 19] (tfu_edge_high_x)
//   dy    [79:0]  channel ch at bits [20ch +: 20] (tfu_edge_high_dy)
//   fv    [7:0]   Q.8
//   chigh [39:0]  channel ch at bits [10ch +: 10]
// Combinational: per channel a signed 20 x 9 multiplier and a 28-bit adder.
module tfu_edge_high_y (
  input  logic [75:0] hx0,
  input  logic [79:0] dy,
  input  logic [7:0]  fv,
  output logic [39:0] chigh
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic signed [18:0] x0;
    logic signed [19:0] d;
    logic signed [27:0] hs;  // |.| <= 255 * 2^16 + 2^15
    assign x0 = hx0[19*ch +: 19];
    assign d = dy[20*ch +: 20];
    assign hs = 28'($signed({x0, 8'd0})) + 28'(d * $signed({1'b0, fv})) + 28'sd32768;
    assign chigh[10*ch +: 10] = 10'(hs >>> 16);
  end
endmodule
