// BC1 decoder for a bilinear footprint (BC1 RGB and BC1 RGBA; Khronos Data Format Specification
// 1.3, "S3TC Compressed Texture Image Formats"; tfu::decode_block with BlockFormat::BC1 / BC1A,
// cmodel/block_formats.hpp): one block and PORTS (default 4) texel positions in it per clock, as
// many RGBA8 texels out. Bit-exact with the C++ decoder for the rule RULE (tfu_bc_pkg::RULE_EXACT,
// the golden rule, or RULE_TRUNCATE, libsquish's and Mesa's). Why four positions of one block:
// docs/sv-bc.md.
//
// Ports:
//   clk, rst_n          rising-edge clock, synchronous active-low reset (clears the valid bits only)
//   en                  clock enable of all stages (stall)
//   in_valid            a request on block, rgba, texel_index
//   block [63:0]        the 8-byte block, byte k in bits [8k+7:8k] (color0 = bytes 0-1, color1 =
//                       bytes 2-3, little endian; the 2-bit code of texel t in bits [32+2t+1:32+2t])
//   rgba                BC1 RGBA (code 3 of 3-colour mode is transparent black) vs BC1 RGB (opaque)
//   texel_index [4 PORTS-1:0]   PORTS texel positions t = 4 y + x in the block (4: a bilinear
//                       footprint's texels in one block; 16: a whole block), port k in bits [4k+3:4k]
//   out_valid, texels [32 PORTS-1:0]   the texels, port k's RGBA8 word in bits [32k+31:32k], registered
//
// Pipeline (latency 2 clocks: a request sampled at rising edge n, with en = 1 at n and n + 1, is on
// out_valid / texels after edge n + 1):
//   S1  input registers
//   S2  palette (tfu_bc1_palette) beside the four 16:1 code selects, then four 4:1 palette selects
//       -> output registers
module tfu_bc1_decode #(
  parameter int RULE = tfu_bc_pkg::RULE_EXACT,
  parameter int PORTS = 4  // texel positions per request
) (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         en,
  input  logic         in_valid,
  input  logic [63:0]  block,
  input  logic         rgba,
  input  logic [4*PORTS-1:0]  texel_index,
  output logic         out_valid,
  output logic [32*PORTS-1:0] texels
);
  // S1
  logic        v1;
  logic [63:0] block_1;
  logic        rgba_1;
  logic [4*PORTS-1:0] index_1;
  always_ff @(posedge clk) begin
    if (!rst_n) v1 <= 1'b0;
    else if (en) v1 <= in_valid;
    if (en) begin
      block_1 <= block;
      rgba_1  <= rgba;
      index_1 <= texel_index;
    end
  end

  // S2
  logic [31:0] p [4];
  tfu_bc1_palette #(.RULE(RULE)) u_palette (
    .color0(block_1[15:0]), .color1(block_1[31:16]), .four_colour_only(1'b0), .three_colour_alpha0(rgba_1),
    .p0(p[0]), .p1(p[1]), .p2(p[2]), .p3(p[3]));
  logic [32*PORTS-1:0] t2;
  for (genvar k = 0; k < PORTS; k++) begin : g_texel
    logic [1:0] code;
    assign code = block_1[32 + 2 * index_1[4*k +: 4] +: 2];
    assign t2[32*k +: 32] = p[code];
  end
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else if (en) out_valid <= v1;
    if (en) texels <= t2;
  end
endmodule
