// Horizontal lerps of the high-frequency parts (Lee & Jen 2003 Eq. 5, exact), per channel; part of
// tfu_edge_merge:
//   hx0 = 256 H4 + fu (H5 - H4),  hx1 = 256 H8 + fu (H9 - H8)   (19 bits signed, |.| <= 255 * 256)
//
// Ports:
//   h   [143:0]  H4, H5, H8, H9 per channel (tfu_edge_high_diff)
//   fu  [7:0]    Q.8
//   hx0 [75:0]   channel ch at bits [19ch +: 19]
//   hx1 [75:0]   channel ch at bits [19ch +: 19]
// Combinational: per channel two 10-bit subtractions and two signed 10 x 9 multipliers.
module tfu_edge_high_x (
  input  logic [143:0] h,
  input  logic [7:0]   fu,
  output logic [75:0]  hx0,
  output logic [75:0]  hx1
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic signed [8:0] h4, h5, h8, h9;  // -255..255
    logic signed [9:0] dx0, dx1;        // H5 - H4, H9 - H8
    assign h4 = h[36*ch +: 9];
    assign h5 = h[36*ch + 9 +: 9];
    assign h8 = h[36*ch + 18 +: 9];
    assign h9 = h[36*ch + 27 +: 9];
    assign dx0 = 10'(h5) - 10'(h4);
    assign dx1 = 10'(h9) - 10'(h8);
    assign hx0[19*ch +: 19] = 19'($signed({h4, 8'd0})) + 19'(dx0 * $signed({1'b0, fu}));
    assign hx1[19*ch +: 19] = 19'($signed({h8, 8'd0})) + 19'(dx1 * $signed({1'b0, fu}));
  end
endmodule
