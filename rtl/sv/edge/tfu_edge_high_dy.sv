// Difference of the horizontal high-frequency lerps (Lee & Jen 2003 Eq. 5), per channel; part of
// tfu_edge_merge:
//   dy = hx1 - hx0   (20 bits signed)
//
// Ports:
//   hx0, hx1 [75:0]  channel ch at bits [19ch +: 19] (tfu_edge_high_x)
//   dy       [79:0]  channel ch at bits [20ch +: 20]
// Combinational: four 20-bit subtractions.
module tfu_edge_high_dy (
  input  logic [75:0] hx0,
  input  logic [75:0] hx1,
  output logic [79:0] dy
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    assign dy[20*ch +: 20] = 20'($signed(hx1[19*ch +: 19])) - 20'($signed(hx0[19*ch +: 19]));
  end
endmodule
