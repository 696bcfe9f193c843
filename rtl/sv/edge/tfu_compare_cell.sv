// Compare cell of the median network (Lee & Jen 2003 Fig. 10): lo = min(a, b), hi = max(a, b),
// unsigned. One comparator and two W-bit 2:1 muxes. Instantiated once per cell of
// rtl::median_netlist() by the generated gen/tfu_median_network.sv.
//
// Ports:
//   a, b   [W-1:0]  keys (unsigned)
//   lo, hi [W-1:0]  the smaller and the larger (a when equal, as std::min; equal keys are equal
//                   values, so the choice does not matter)
// Combinational.
module tfu_compare_cell #(
  parameter int W = 16
) (
  input  logic [W-1:0] a,
  input  logic [W-1:0] b,
  output logic [W-1:0] lo,
  output logic [W-1:0] hi
);
  logic b_lt_a;
  assign b_lt_a = b < a;
  assign lo = b_lt_a ? b : a;
  assign hi = b_lt_a ? a : b;
endmodule
