// Merge of the low- and high-frequency parts (Lee & Jen 2003 Eq. 6), per channel; the last part of
// tfu_edge_merge:
//   I = clamp(C_low + C_high, 0, 255)   (11 bits signed, -255..510, before the clamp)
//
// Ports:
//   clow  [31:0]  C_low per channel (tfu_edge_low_lerp)
//   chigh [39:0]  C_high, channel ch at bits [10ch +: 10] (tfu_edge_high_y)
//   c     [31:0]  interpolated texel
// Combinational.
module tfu_edge_sum_clamp (
  input  logic [31:0] clow,
  input  logic [39:0] chigh,
  output logic [31:0] c
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic signed [10:0] sum;
    assign sum = $signed({3'b000, clow[8*ch +: 8]}) + 11'($signed(chigh[10*ch +: 10]));
    assign c[8*ch +: 8] = sum < 0 ? 8'd0 : (sum > 11'sd255 ? 8'd255 : 8'(sum));
  end
endmodule
