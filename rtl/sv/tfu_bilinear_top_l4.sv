// tfu_bilinear_top with latency 4 (CUT_V = 1: a register inside the vertical lerp): the depth that
// meets 101.2 MHz in OSU 0.35 um at the typical corner (docs/silicon.md). Ports as tfu_bilinear_top.
module tfu_bilinear_top_l4 (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        en,
  input  logic        in_valid,
  input  logic [31:0] c00,
  input  logic [31:0] c10,
  input  logic [31:0] c01,
  input  logic [31:0] c11,
  input  logic [7:0]  fu,
  input  logic [7:0]  fv,
  output logic        out_valid,
  output logic [63:0] q,
  output logic [31:0] c
);
  tfu_bilinear_top #(.CUT_V(1'b1)) u_top (.clk(clk), .rst_n(rst_n), .en(en), .in_valid(in_valid), .c00(c00), .c10(c10), .c01(c01),
                                          .c11(c11), .fu(fu), .fv(fv), .out_valid(out_valid),
                                          .q(q), .c(c));
endmodule
