// tfu_edge_interp_top with latency 8 (CUTS = 8'b1101_1111: a register after every step but the
// direction's, whose step 5 shares a stage with the endpoint select): the depth that meets
// 101.2 MHz in OSU 0.35 um at the typical corner (docs/silicon.md). Ports as tfu_edge_interp_top.
module tfu_edge_interp_top_l8 (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         in_valid,
  input  logic [383:0] texels,
  input  logic [11:0]  shape,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic         out_valid,
  output logic [31:0]  c
);
  tfu_edge_interp_top #(.CUTS(8'b1101_1111)) u_top (.clk(clk), .rst_n(rst_n), .in_valid(in_valid), .texels(texels), .shape(shape),
                                                    .fu(fu), .fv(fv), .out_valid(out_valid), .c(c));
endmodule
