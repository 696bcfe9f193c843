// BC4 UNORM decoder for a bilinear footprint (Khronos Data Format Specification 1.3, "RGTC
// Compressed Texture Image Formats"; tfu::decode_block with BlockFormat::BC4,
// cmodel/block_formats.hpp): one block and PORTS (default 4) texel positions in it per clock, as
// many texels out as the unit sees a RED texture, (r, 0, 0, 255). Bit-exact with the C++ decoder
// for the rule RULE (tfu_bc_pkg::RULE_EXACT, the golden rule, or RULE_TRUNCATE). Why four positions
// of one block: docs/sv-bc.md.
//
// Ports:
//   clk, rst_n, en, in_valid    as tfu_bc1_decode
//   block [63:0]        the 8-byte block, byte k in bits [8k+7:8k] (red0 = byte 0, red1 = byte 1;
//                       the 3-bit code of texel t in bits [16+3t+2:16+3t])
//   texel_index [4 PORTS-1:0]   PORTS texel positions t = 4 y + x in the block (4: a bilinear
//                       footprint's texels in one block; 16: a whole block), port k in bits [4k+3:4k]
//   out_valid, texels [32 PORTS-1:0]   the texels, port k's RGBA8 word in bits [32k+31:32k], registered
//
// Pipeline (latency 2 clocks, as tfu_bc1_decode):
//   S1  input registers
//   S2  eight values (tfu_bc4_palette) beside the four 16:1 code selects, then four 8:1 value
//       selects -> output registers
module tfu_bc4_decode #(
  parameter int RULE = tfu_bc_pkg::RULE_EXACT,
  parameter int PORTS = 4  // texel positions per request
) (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         en,
  input  logic         in_valid,
  input  logic [63:0]  block,
  input  logic [4*PORTS-1:0]  texel_index,
  output logic         out_valid,
  output logic [32*PORTS-1:0] texels
);
  // S1
  logic        v1;
  logic [63:0] block_1;
  logic [4*PORTS-1:0] index_1;
  always_ff @(posedge clk) begin
    if (!rst_n) v1 <= 1'b0;
    else if (en) v1 <= in_valid;
    if (en) begin
      block_1 <= block;
      index_1 <= texel_index;
    end
  end

  // S2
  logic [63:0] vals;
  tfu_bc4_palette #(.RULE(RULE)) u_palette (.a0(block_1[7:0]), .a1(block_1[15:8]), .p(vals));
  logic [32*PORTS-1:0] t2;
  for (genvar k = 0; k < PORTS; k++) begin : g_texel
    logic [2:0] code;
    assign code = block_1[16 + 3 * index_1[4*k +: 4] +: 3];
    assign t2[32*k +: 32] = {8'hff, 16'h0000, vals[8 * code +: 8]};
  end
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else if (en) out_valid <= v1;
    if (en) texels <= t2;
  end
endmodule
