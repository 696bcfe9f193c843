// Compare cell of the median network (Lee & Jen 2003 Sec. 6, Fig. 10): lo = min(a, b),
// hi = max(a, b), and the flag a_gt_b = a > b ("the larger result from the right-hand side, the
// smaller result from the left-hand side, and a one-bit flag indicating comparison result"),
// unsigned. One comparator and two W-bit 2:1 muxes. Instantiated once per cell of
// rtl::median_netlist() by the generated gen/tfu_median_network.sv; where only the flag is read (the
// cells of a three-point median), synthesis removes the muxes.
//
// Ports:
//   a, b    [W-1:0]  keys (unsigned)
//   lo, hi  [W-1:0]  the smaller and the larger (a when equal, as std::min; equal keys are equal
//                    values, so the choice does not matter)
//   a_gt_b           1 when a > b
// Combinational.
module tfu_compare_cell #(
  parameter int W = 16
) (
  input  logic [W-1:0] a,
  input  logic [W-1:0] b,
  output logic [W-1:0] lo,
  output logic [W-1:0] hi,
  output logic         a_gt_b
);
  assign a_gt_b = b < a;
  assign lo = a_gt_b ? b : a;
  assign hi = a_gt_b ? a : b;
endmodule
