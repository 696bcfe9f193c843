// One optional pipeline register of a pipelined top: a data word and its valid bit, registered when
// REG = 1, wires when REG = 0 (the pipeline depth of a top is a parameter: its cut points choose
// which of these are registers).
//
// Ports:
//   clk, rst_n  rising-edge clock, synchronous active-low reset (clears the valid bit only)
//   vin, d      valid bit and data word [W-1:0] into the cut
//   vout, q     the same, one clock later (REG = 1) or at once (REG = 0)
module tfu_pipe_reg #(
  parameter int W = 1,
  parameter bit REG = 1'b1
) (
  /* verilator lint_off UNUSEDSIGNAL */  // clk and rst_n are not read when REG = 0
  input  logic         clk,
  input  logic         rst_n,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic         vin,
  input  logic [W-1:0] d,
  output logic         vout,
  output logic [W-1:0] q
);
  if (REG) begin : g_reg
    always_ff @(posedge clk) begin
      if (!rst_n) vout <= 1'b0;
      else vout <= vin;
      q <= d;
    end
  end else begin : g_wire
    assign vout = vin;
    assign q = d;
  end
endmodule
