// Colour differences of the 22 directions (Lee & Jen 2003 Eq. 1), RGBA8; the first part of
// tfu_edge_dir_select:
//   dp_i = |dR| + |dG| + |dB| between the low-pass endpoints Cp_low, Cq_low of direction i
//          (10 bits, 0..765)
// Direction endpoints: package tfu_edge_pkg (gen/tfu_edge_pkg.sv, from lee_jen::directions()).
//
// Ports:
//   lowrgb [287:0]  R, G, B of Cn_low at bits [24(n-1) +: 24] (R in the low byte)
//   dp     [219:0]  dp_i at bits [10i +: 10], i = 0..21
// Combinational: per direction three 8-bit |a - b| and a 10-bit sum.
module tfu_edge_dir_dp (
  input  logic [287:0]                     lowrgb,
  output logic [10*tfu_edge_pkg::NDIR-1:0] dp
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam logic [4*NDIR-1:0] DIR_P = tfu_edge_pkg::DIR_P;
  localparam logic [4*NDIR-1:0] DIR_Q = tfu_edge_pkg::DIR_Q;

  function automatic logic [9:0] absdiff(input logic [7:0] a, input logic [7:0] b);
    absdiff = a > b ? {2'b00, a - b} : {2'b00, b - a};
  endfunction

  for (genvar i = 0; i < NDIR; i++) begin : g_dir
    localparam int P = 32'(DIR_P[4*i +: 4]) - 1;  // texel index of Cp (bit of shape)
    localparam int Q = 32'(DIR_Q[4*i +: 4]) - 1;
    assign dp[10*i +: 10] = absdiff(lowrgb[24*P +: 8], lowrgb[24*Q +: 8]) + absdiff(lowrgb[24*P + 8 +: 8], lowrgb[24*Q + 8 +: 8]) +
                            absdiff(lowrgb[24*P + 16 +: 8], lowrgb[24*Q + 16 +: 8]);
  end
endmodule
