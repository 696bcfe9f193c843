// BC7 decoder for a bilinear footprint (BPTC RGBA UNORM, all eight modes; Khronos Data Format
// Specification 1.3, "BPTC Compressed Texture Image Formats"; tfu::decode_block with
// BlockFormat::BC7, cmodel/bc7_decode.hpp): one block and PORTS (default 4) texel positions in it
// per clock, as many RGBA8 texels out, bit-exact (BC7 leaves no rounding to the implementation).
// Same interface as tfu_bc3_decode (docs/sv-bc.md).
//
// Ports:
//   clk, rst_n, en, in_valid    as tfu_bc1_decode
//   block [127:0]       the 16-byte block, byte k in bits [8k+7:8k]
//   texel_index [4 PORTS-1:0]   PORTS texel positions t = 4 y + x in the block (4: a bilinear
//                       footprint's texels in one block; 16: a whole block), port k in bits [4k+3:4k]
//   out_valid, texels [32 PORTS-1:0]   the texels, port k's RGBA8 word in bits [32k+31:32k], registered
//
// Pipeline (latency 3 clocks: a request sampled at rising edge n, with en = 1 at n .. n + 2, is on
// out_valid / texels after edge n + 2):
//   S1  input registers
//   S2  unpack (gen/tfu_bc7_unpack.sv: mode, partition ROMs, widened endpoints, indices with the
//       anchor bits restored) -> registers
//   S3  per port: the texel's subset and indices, the weights (tfu_bc7_weight), four interpolations
//       c = ((64 - w) e0 + w e1 + 32) >> 6 (8 x 7-bit products, 15-bit sum), the rotation
//       -> output registers
module tfu_bc7_decode #(
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
  logic         reserved;
  logic [191:0] endpoints;
  logic [31:0]  subset;
  logic [63:0]  index1;
  logic [47:0]  index2;
  logic [2:0]   bits1, bits2;
  logic         index_sel;
  logic [1:0]   rotation;
  tfu_bc7_unpack u_unpack (.block(block_1), .reserved(reserved), .endpoints(endpoints), .subset(subset),
                           .index1(index1), .index2(index2), .bits1(bits1), .bits2(bits2),
                           .index_sel(index_sel), .rotation(rotation));
  logic         v2, reserved_2, index_sel_2;
  logic [191:0] endpoints_2;
  logic [31:0]  subset_2;
  logic [63:0]  index1_2;
  logic [47:0]  index2_2;
  logic [2:0]   bits1_2, bits2_2;
  logic [1:0]   rotation_2;
  logic [4*PORTS-1:0]  index_2;
  always_ff @(posedge clk) begin
    if (!rst_n) v2 <= 1'b0;
    else if (en) v2 <= v1;
    if (en) begin
      reserved_2  <= reserved;
      endpoints_2 <= endpoints;
      subset_2    <= subset;
      index1_2    <= index1;
      index2_2    <= index2;
      bits1_2     <= bits1;
      bits2_2     <= bits2;
      index_sel_2 <= index_sel;
      rotation_2  <= rotation;
      index_2     <= index_1;
    end
  end

  // S3
  logic [32*PORTS-1:0] t3;
  for (genvar k = 0; k < PORTS; k++) begin : g_texel
    logic [3:0]  t;
    logic [1:0]  s;
    logic [3:0]  i1;
    logic [2:0]  i2;
    logic [3:0]  ci, ai;        // colour and alpha index
    logic [2:0]  cbits, abits;  // their widths
    logic [6:0]  cw, aw;        // their weights, 0..64
    logic [7:0]  c [4];
    assign t = index_2[4*k +: 4];
    assign s = subset_2[2*t +: 2];
    assign i1 = index1_2[4*t +: 4];
    assign i2 = index2_2[3*t +: 3];
    // No secondary index: both from the primary. Otherwise colour from the secondary when index_sel
    // (alpha from the primary), else colour from the primary and alpha from the secondary.
    always_comb begin
      ci = i1;
      cbits = bits1_2;
      ai = i1;
      abits = bits1_2;
      if (bits2_2 != 3'd0) begin
        if (index_sel_2) begin
          ci = {1'b0, i2};
          cbits = bits2_2;
        end else begin
          ai = {1'b0, i2};
          abits = bits2_2;
        end
      end
    end
    tfu_bc7_weight u_cw (.bits(cbits), .index(ci), .weight(cw));
    tfu_bc7_weight u_aw (.bits(abits), .index(ai), .weight(aw));
    for (genvar ch = 0; ch < 4; ch++) begin : g_ch
      logic [7:0]  e0, e1;
      logic [6:0]  w;
      assign e0 = endpoints_2[8 * (6 * ch + 2 * s) +: 8];
      assign e1 = endpoints_2[8 * (6 * ch + 2 * s + 1) +: 8];
      assign w = ch == 3 ? aw : cw;
      // (64 - w) e0 + w e1 + 32 <= 64 * 255 + 32: 15 bits; the result is below 256.
      assign c[ch] = 8'(((15'd64 - 15'(w)) * 15'(e0) + 15'(w) * 15'(e1) + 15'd32) >> 6);
    end
    // Rotation (modes 4, 5): swap alpha with R (1), G (2) or B (3).
    logic [31:0] rgba;
    always_comb begin
      rgba = {c[3], c[2], c[1], c[0]};
      case (rotation_2)
        2'd1: rgba = {c[0], c[2], c[1], c[3]};
        2'd2: rgba = {c[1], c[2], c[3], c[0]};
        2'd3: rgba = {c[2], c[3], c[1], c[0]};
        default: ;
      endcase
    end
    assign t3[32*k +: 32] = reserved_2 ? 32'd0 : rgba;
  end
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else if (en) out_valid <= v2;
    if (en) texels <= t3;
  end
endmodule
