// BC3 decoder for a bilinear footprint (Khronos Data Format Specification 1.3, "S3TC Compressed
// Texture Image Formats"; tfu::decode_block with BlockFormat::BC3, cmodel/block_formats.hpp): a
// BC4-style alpha block (bytes 0-7, tfu_bc4_palette) and a BC1 colour block always decoded in
// 4-colour mode (bytes 8-15, tfu_bc1_palette), one block and PORTS (default 4) texel positions in
// it per clock, as many RGBA8 texels out. Bit-exact with the C++ decoder for the rule RULE
// (tfu_bc_pkg::RULE_EXACT, the golden rule, for colour and alpha, or RULE_TRUNCATE for both). Why
// four positions of one block: docs/sv-bc.md.
//
// Ports:
//   clk, rst_n, en, in_valid    as tfu_bc1_decode
//   block [127:0]       the 16-byte block, byte k in bits [8k+7:8k]: alpha0 = byte 0, alpha1 = byte 1,
//                       alpha code of texel t in bits [16+3t+2:16+3t]; color0 = bytes 8-9,
//                       color1 = bytes 10-11, colour code of texel t in bits [96+2t+1:96+2t]
//   texel_index [4 PORTS-1:0]   PORTS texel positions t = 4 y + x in the block (4: a bilinear
//                       footprint's texels in one block; 16: a whole block), port k in bits [4k+3:4k]
//   out_valid, texels [32 PORTS-1:0]   the texels, port k's RGBA8 word in bits [32k+31:32k], registered
//
// Pipeline (latency 2 clocks, as tfu_bc1_decode):
//   S1  input registers
//   S2  colour palette and alpha values beside the code selects, then the palette selects
//       -> output registers
module tfu_bc3_decode #(
  parameter int RULE = tfu_bc_pkg::RULE_EXACT,
  parameter int PORTS = 4  // texel positions per request
) (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         en,
  input  logic         in_valid,
  input  logic [127:0] block,
  input  logic [4*PORTS-1:0]  texel_index,
  output logic         out_valid,
  output logic [32*PORTS-1:0] texels
);
  // S1
  logic         v1;
  logic [127:0] block_1;
  logic [4*PORTS-1:0]  index_1;
  always_ff @(posedge clk) begin
    if (!rst_n) v1 <= 1'b0;
    else if (en) v1 <= in_valid;
    if (en) begin
      block_1 <= block;
      index_1 <= texel_index;
    end
  end

  // S2
  logic [63:0] alpha;
  tfu_bc4_palette #(.RULE(RULE)) u_alpha (.a0(block_1[7:0]), .a1(block_1[15:8]), .p(alpha));
  // The colour palette's alpha byte (always 255 in 4-colour mode) is not used: alpha is the BC4 half's.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [31:0] p [4];
  /* verilator lint_on UNUSEDSIGNAL */
  tfu_bc1_palette #(.RULE(RULE)) u_colour (
    .color0(block_1[79:64]), .color1(block_1[95:80]), .four_colour_only(1'b1), .three_colour_alpha0(1'b0),
    .p0(p[0]), .p1(p[1]), .p2(p[2]), .p3(p[3]));
  logic [32*PORTS-1:0] t2;
  for (genvar k = 0; k < PORTS; k++) begin : g_texel
    logic [2:0] acode;
    logic [1:0] ccode;
    assign acode = block_1[16 + 3 * index_1[4*k +: 4] +: 3];
    assign ccode = block_1[96 + 2 * index_1[4*k +: 4] +: 2];
    assign t2[32*k +: 32] = {alpha[8 * acode +: 8], p[ccode][23:0]};
  end
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else if (en) out_valid <= v1;
    if (en) texels <= t2;
  end
endmodule
