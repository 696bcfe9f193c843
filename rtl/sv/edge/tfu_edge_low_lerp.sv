// Directional interpolation of the low-pass endpoints (Lee & Jen 2003 Eq. 3), per channel (alpha
// included); part of tfu_edge_merge:
//   C_low = ((256 - t) Cp_low + t Cq_low + 128) >> 8 = (256 Cp_low + t (Cq_low - Cp_low) + 128) >> 8
//           (one signed 9 x 9 multiplier per channel)
//
// Ports:
//   cp, cq [31:0]  endpoints (RGBA, R in the low byte; tfu_edge_endpoints)
//   t      [7:0]   blend parameter, Q.8
//   clow   [31:0]  C_low per channel
// Combinational.
module tfu_edge_low_lerp (
  input  logic [31:0] cp,
  input  logic [31:0] cq,
  input  logic [7:0]  t,
  output logic [31:0] clow
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic signed [8:0]  dq;  // Cq - Cp, -255..255
    logic signed [17:0] lw;  // 256 Cp + t (Cq - Cp) + 128, 128..65408
    assign dq = $signed({1'b0, cq[8*ch +: 8]}) - $signed({1'b0, cp[8*ch +: 8]});
    assign lw = $signed({2'b00, cp[8*ch +: 8], 8'd128}) + 18'(dq * $signed({1'b0, t}));
    assign clow[8*ch +: 8] = 8'(lw >>> 8);
  end
endmodule
