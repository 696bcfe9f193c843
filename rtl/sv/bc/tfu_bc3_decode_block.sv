// tfu_bc3_decode with 16 ports, port k wired to texel k: a whole BC3 block per clock, the decoder a
// decode-on-fill texel cache wants (docs/sv-bc.md). Ports and pipeline as tfu_bc3_decode without
// texel_index; the golden rule EXACT; the constant positions reduce the selects of the 16 ports to wiring.
//   texels [511:0]   texel t = 4 y + x of the block in bits [32t+31:32t], registered
module tfu_bc3_decode_block (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         en,
  input  logic         in_valid,
  input  logic [127:0] block,
  output logic         out_valid,
  output logic [511:0] texels
);
  logic [63:0] every_texel;  // port k reads texel k
  for (genvar k = 0; k < 16; k++) begin : g_index
    assign every_texel[4*k +: 4] = 4'(k);
  end
  tfu_bc3_decode #(.PORTS(16)) u_decode (.clk(clk), .rst_n(rst_n), .en(en), .in_valid(in_valid), .block(block),
                                       .texel_index(every_texel), .out_valid(out_valid), .texels(texels));
endmodule
