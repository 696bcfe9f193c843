// The eight values of a BC4 UNORM block (BC3 alpha, BC4 red, each half of BC5; Khronos Data Format
// Specification 1.3, "RGTC Compressed Texture Image Formats"; tfu::decode_bc4_unorm8,
// cmodel/bc_decode.hpp). Combinational.
//
// Value c of endpoints a0, a1 (8 bits), b7 / b5 the rule's biases (RULE_EXACT: 3 / 2, round to
// nearest of the spec's real value; RULE_TRUNCATE: 0 / 0, floor):
//   c = 0, 1               a0, a1
//   a0 > a1 (8 values)     ((8 - c) a0 + (c - 1) a1 + b7) / 7     c = 2..7  (numerator 11 bits, <= 1788)
//   a0 <= a1 (6 values)    ((6 - c) a0 + (c - 1) a1 + b5) / 5     c = 2..5  (<= 1277)
//                          0 (c = 6), 255 (c = 7)
// round(s / 7) = (s + 3) / 7 and round(s / 5) = (s + 2) / 5 because s / 7 and s / 5 are never a
// half. The weights are constants, so each numerator is a sum of shifted endpoints; each division a
// multiply by DIV7_MUL / DIV5_MUL and a shift (gen/tfu_bc_pkg.sv, checked exhaustively against the
// C++ by tfu_svgen).
//
// Ports:
//   a0, a1 [7:0]   the block's endpoints (bytes 0 and 1)
//   p [63:0]       value c in bits [8c+7:8c]
module tfu_bc4_palette #(
  parameter int RULE = tfu_bc_pkg::RULE_EXACT
) (
  input  logic [7:0]  a0,
  input  logic [7:0]  a1,
  output logic [63:0] p
);
  localparam int X7 = tfu_bc_pkg::DIV7_X_BITS;
  localparam int X5 = tfu_bc_pkg::DIV5_X_BITS;
  localparam int P7 = tfu_bc_pkg::DIV7_SHIFT + 8;  // product bits: every quotient is < 256
  localparam int P5 = tfu_bc_pkg::DIV5_SHIFT + 8;
  localparam logic [X7-1:0] B7 = X7'(RULE == tfu_bc_pkg::RULE_EXACT ? tfu_bc_pkg::BC4_SEVENTH_BIAS_EXACT
                                                                    : tfu_bc_pkg::BC4_SEVENTH_BIAS_TRUNCATE);
  localparam logic [X5-1:0] B5 = X5'(RULE == tfu_bc_pkg::RULE_EXACT ? tfu_bc_pkg::BC4_FIFTH_BIAS_EXACT
                                                                    : tfu_bc_pkg::BC4_FIFTH_BIAS_TRUNCATE);

  logic eight;
  assign eight = a0 > a1;
  assign p[7:0] = a0;
  assign p[15:8] = a1;
  for (genvar c = 2; c < 8; c++) begin : g_val
    logic [X7-1:0] s7;
    logic [7:0]    q7;  // the 8-value mode's value c
    logic [7:0]    v5;  // the 6-value mode's value c
    assign s7 = X7'(8 - c) * X7'(a0) + X7'(c - 1) * X7'(a1) + B7;
    assign q7 = 8'((P7'(s7) * P7'(tfu_bc_pkg::DIV7_MUL)) >> tfu_bc_pkg::DIV7_SHIFT);
    if (c < 6) begin : g_fifth
      logic [X5-1:0] s5;
      assign s5 = X5'(6 - c) * X5'(a0) + X5'(c - 1) * X5'(a1) + B5;
      assign v5 = 8'((P5'(s5) * P5'(tfu_bc_pkg::DIV5_MUL)) >> tfu_bc_pkg::DIV5_SHIFT);
    end else begin : g_const
      assign v5 = c == 6 ? 8'd0 : 8'd255;
    end
    assign p[8*c +: 8] = eight ? q7 : v5;
  end
endmodule
