// The four colours of a BC1 colour block (Khronos Data Format Specification 1.3, "S3TC Compressed
// Texture Image Formats"; tfu::bc1_palette, cmodel/bc_decode.hpp). Combinational.
//
// Per channel (R: bits [15:11], G: [10:5], B: [4:0] of a 16-bit colour): the n-bit fields v0, v1
// widened to 8 bits by bit replication, e = (v << 3) | (v >> 2) (n = 5), (v << 2) | (v >> 4) (n = 6);
// then, with b the rule's bias (RULE_EXACT: 1, round to nearest; RULE_TRUNCATE: 0, floor):
//   4-colour mode (four_colour_only, or color0 > color1 as 16-bit integers):
//     p2 = (2 e0 + e1 + b) / 3, p3 = (e0 + 2 e1 + b) / 3          (numerators 10 bits, <= 766)
//   3-colour mode: p2 = (e0 + e1 + b) >> 1, p3 = black
// The division by 3 is a multiply by DIV3_MUL and a shift by DIV3_SHIFT (gen/tfu_bc_pkg.sv, derived
// and checked exhaustively against the C++ by tfu_svgen). Alpha: 255, except p3 of 3-colour mode
// when three_colour_alpha0 (BC1 RGBA's transparent black).
//
// Ports:
//   color0, color1 [15:0]   the block's two colours (bytes 0-1 and 2-3, little endian)
//   four_colour_only        BC2/BC3 colour blocks (no 3-colour mode)
//   three_colour_alpha0     BC1 RGBA: p3 of 3-colour mode has alpha 0
//   p0, p1, p2, p3 [31:0]   the palette, RGBA8 (channel k in bits [8k+7:8k])
module tfu_bc1_palette #(
  parameter int RULE = tfu_bc_pkg::RULE_EXACT
) (
  input  logic [15:0] color0,
  input  logic [15:0] color1,
  input  logic        four_colour_only,
  input  logic        three_colour_alpha0,
  output logic [31:0] p0,
  output logic [31:0] p1,
  output logic [31:0] p2,
  output logic [31:0] p3
);
  localparam int XB = tfu_bc_pkg::DIV3_X_BITS;  // numerator bits
  localparam int PB = tfu_bc_pkg::DIV3_SHIFT + 8;  // product bits: every quotient is < 256
  localparam logic [XB-1:0] THIRD_BIAS = XB'(RULE == tfu_bc_pkg::RULE_EXACT ? tfu_bc_pkg::BC1_THIRD_BIAS_EXACT
                                                                            : tfu_bc_pkg::BC1_THIRD_BIAS_TRUNCATE);
  localparam logic [8:0] HALF_BIAS = 9'(RULE == tfu_bc_pkg::RULE_EXACT ? tfu_bc_pkg::BC1_HALF_BIAS_EXACT
                                                                      : tfu_bc_pkg::BC1_HALF_BIAS_TRUNCATE);
  localparam logic [PB-1:0] DIV3_MUL = PB'(tfu_bc_pkg::DIV3_MUL);

  logic four;
  assign four = four_colour_only | (color0 > color1);

  logic [7:0] e0 [3];
  logic [7:0] e1 [3];
  assign e0[0] = {color0[15:11], color0[15:13]};
  assign e1[0] = {color1[15:11], color1[15:13]};
  assign e0[1] = {color0[10:5], color0[10:9]};
  assign e1[1] = {color1[10:5], color1[10:9]};
  assign e0[2] = {color0[4:0], color0[4:2]};
  assign e1[2] = {color1[4:0], color1[4:2]};

  logic [7:0] c2 [3];
  logic [7:0] c3 [3];
  for (genvar ch = 0; ch < 3; ch++) begin : g_ch
    logic [XB-1:0] n02, n13;  // 2 e0 + e1 + b, e0 + 2 e1 + b
    logic [7:0]    q02, q13;  // n / 3
    logic [7:0]    h;         // (e0 + e1 + b) >> 1
    assign n02 = XB'({e0[ch], 1'b0}) + XB'(e1[ch]) + THIRD_BIAS;
    assign n13 = XB'(e0[ch]) + XB'({e1[ch], 1'b0}) + THIRD_BIAS;
    assign q02 = 8'((PB'(n02) * DIV3_MUL) >> tfu_bc_pkg::DIV3_SHIFT);
    assign q13 = 8'((PB'(n13) * DIV3_MUL) >> tfu_bc_pkg::DIV3_SHIFT);
    assign h = 8'((9'(e0[ch]) + 9'(e1[ch]) + HALF_BIAS) >> 1);
    assign c2[ch] = four ? q02 : h;
    assign c3[ch] = four ? q13 : 8'd0;
  end

  assign p0 = {8'hff, e0[2], e0[1], e0[0]};
  assign p1 = {8'hff, e1[2], e1[1], e1[0]};
  assign p2 = {8'hff, c2[2], c2[1], c2[0]};
  assign p3 = {(!four && three_colour_alpha0) ? 8'h00 : 8'hff, c3[2], c3[1], c3[0]};
endmodule
