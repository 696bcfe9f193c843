// Final selector of a three-point median (Lee & Jen 2003 Sec. 6, Fig. 10: "three comparison cells
// in parallel and a final selector"): from the flags of the three cells on (a, b), (a, c), (b, c),
// the median is b when a > b and b > c agree (a > b > c or a <= b <= c), else a when a > b and
// a > c differ (a between b and c), else c. With ties the choice is one of the equal values.
// Instantiated once per median by the generated gen/tfu_median_network.sv (rtl::Median3Select),
// on the texel-number bits [3:0] of the keys.
//
// Ports:
//   a_gt_b, a_gt_c, b_gt_c   flags of the three compare cells
//   a, b, c  [W-1:0]         the values to select from
//   m        [W-1:0]         the median
// Combinational: two W-bit 2:1 muxes and their select logic.
module tfu_median3_select #(
  parameter int W = 4
) (
  input  logic         a_gt_b,
  input  logic         a_gt_c,
  input  logic         b_gt_c,
  input  logic [W-1:0] a,
  input  logic [W-1:0] b,
  input  logic [W-1:0] c,
  output logic [W-1:0] m
);
  assign m = (a_gt_b == b_gt_c) ? b : ((a_gt_b != a_gt_c) ? a : c);
endmodule
