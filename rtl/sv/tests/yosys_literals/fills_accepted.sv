// Accepted by scripts/gate_count: fills that Yosys 0.23 and Verilator read alike. '1 outside a
// parameter value (an assignment takes the target's width in both tools), '0 in a parameter (zero
// either way), replications, sized literals and casts; '1 in a comment: localparam P = '1.
module fills_accepted #(
  parameter int W = 16
) (
  input  logic [3:0]   n,
  output logic [W-1:0] a,
  output logic [W-1:0] b,
  output logic [W-1:0] c,
  output logic [3:0]   d
);
  localparam logic [W-1:0] ONES = {W{1'b1}};  /* not '1 */
  localparam logic [W-1:0] ZERO = '0;
  localparam logic [7:0] MASK = 8'hff;
  assign a = ONES & {8'h0, MASK};
  assign b = n[0] ? ZERO : '1;
  assign c = '1;
  assign d = 4'(n + 1);
endmodule
