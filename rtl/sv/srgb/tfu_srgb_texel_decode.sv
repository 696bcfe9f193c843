// Texel decode of the 8-bit formats into the filter's channels (cmodel/texture.hpp decode_texel;
// docs/srgb.md). RGBA8 (srgb = 0): each byte zero-extended to 12 bits. SRGBA8 (srgb = 1): R, G, B
// through the decode ROM to linear unorm12 (0..4095), A zero-extended (alpha is linear).
// Ports:
//   word [31:0]  texel word, R in [7:0], G [15:8], B [23:16], A [31:24]
//   srgb         the texture descriptor's format is srgba8
//   c    [47:0]  channels, R in [11:0], G [23:12], B [35:24], A [47:36]
// Combinational.
module tfu_srgb_texel_decode (
  input  logic [31:0] word,
  input  logic        srgb,
  output logic [47:0] c
);
  logic [11:0] lin [3];
  for (genvar k = 0; k < 3; k++) begin : g_rom
    tfu_srgb_decode_rom u_rom (.code(word[8*k +: 8]), .linear(lin[k]));
    assign c[12*k +: 12] = srgb ? lin[k] : {4'd0, word[8*k +: 8]};
  end
  assign c[47:36] = {4'd0, word[31:24]};
endmodule
