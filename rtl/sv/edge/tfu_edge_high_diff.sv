// High-frequency parts of the centre square (Lee & Jen 2003 Eq. 5), per channel (alpha included);
// part of tfu_edge_merge:
//   H_n = C_n - Cn_low, n = 4, 5, 8, 9   (9 bits signed, -255..255)
//
// Ports:
//   centre [127:0]  C4, C5, C8, C9 (RGBA) at bits [0 +: 32], [32 +: 32], [64 +: 32], [96 +: 32]
//   lowc   [127:0]  C4_low, C5_low, C8_low, C9_low in the same order
//   h      [143:0]  channel ch at bits [36ch +: 36]: H4, H5, H8, H9 at [0 +: 9], [9 +: 9], [18 +: 9], [27 +: 9]
// Combinational: sixteen 9-bit subtractions.
module tfu_edge_high_diff (
  input  logic [127:0] centre,
  input  logic [127:0] lowc,
  output logic [143:0] h
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    for (genvar k = 0; k < 4; k++) begin : g_n
      assign h[36*ch + 9*k +: 9] = $signed({1'b0, centre[32*k + 8*ch +: 8]}) - $signed({1'b0, lowc[32*k + 8*ch +: 8]});
    end
  end
endmodule
