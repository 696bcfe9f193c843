// Weighted costs of the 22 directions (Lee & Jen 2003 Eq. 2, Sec. 3), the leaves of the direction
// select's min tree; the second part of tfu_edge_dir_select:
//   cost_i = w_i * dp_i (18 bits, at most 254 * 765 = 194310)
//   usable = both endpoints available in `shape` and w_i != 255 (the ROM's "never choose")
// Direction endpoints: package tfu_edge_pkg (gen/tfu_edge_pkg.sv).
//
// Ports:
//   dp    [219:0]  dp_i at bits [10i +: 10] (tfu_edge_dir_dp)
//   w     [175:0]  weight code of direction i at bits [8i +: 8] (tfu_edge_dir_roms, 4.4)
//   shape [11:0]   available texels, bit n-1 = Cn
//   leaf  [767:0]  leaf k at bits [24k +: 24] = {usable, cost[17:0], index[4:0]}, k = 0..31;
//                  leaves 22..31 are all zeros (unusable)
// Combinational: 22 8 x 10 multipliers.
module tfu_edge_dir_leaves (
  input  logic [10*tfu_edge_pkg::NDIR-1:0] dp,
  input  logic [8*tfu_edge_pkg::NDIR-1:0]  w,
  input  logic [11:0]                      shape,
  output logic [32*24-1:0]                 leaf
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam logic [4*NDIR-1:0] DIR_P = tfu_edge_pkg::DIR_P;
  localparam logic [4*NDIR-1:0] DIR_Q = tfu_edge_pkg::DIR_Q;
  for (genvar i = 0; i < 32; i++) begin : g_dir
    if (i < NDIR) begin : g_used
      localparam int P = 32'(DIR_P[4*i +: 4]) - 1;
      localparam int Q = 32'(DIR_Q[4*i +: 4]) - 1;
      logic [7:0]  wi;
      logic [17:0] c;
      assign wi = w[8*i +: 8];
      assign c = {10'b0, wi} * {8'b0, dp[10*i +: 10]};
      assign leaf[24*i +: 24] = {shape[P] & shape[Q] & (wi != 8'hFF), c, 5'(i)};
    end else begin : g_pad
      assign leaf[24*i +: 24] = '0;
    end
  end
endmodule
