// Refused by scripts/gate_count: a localparam filled with the unbased unsized literal '1, which Yosys
// 0.23 reads as 16'h0001 (Verilator: 16'hffff). The minimal reproducer of docs/silicon-log.md
// (2026-12-06): `yosys -p "read_verilog -sv param_fill.sv; proc; opt; write_verilog -noattr -"` prints
// `assign y_param = s ? 16'h1234 : 16'h0001;` beside `assign y_direct = s ? 16'h1234 : 16'hffff;`.
module param_fill (
  input  logic        s,
  output logic [15:0] y_param,
  output logic [15:0] y_direct
);
  localparam logic [15:0] ONES = '1;
  assign y_param = s ? 16'h1234 : ONES;
  assign y_direct = s ? 16'h1234 : '1;
endmodule
