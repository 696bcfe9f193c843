// Result encode at the unit's 8-bit output port (cmodel/texture.hpp encode_texel; docs/srgb.md):
// RGBA8 (srgb = 0): each channel's low byte (the filter's 8-bit result, 0..255). SRGBA8 (srgb = 1):
// R, G, B (linear unorm12) through the encode ROM to 8-bit sRGB codes; A the low byte.
// Ports:
//   c    [47:0]  filtered channels (within the format's range), R in [11:0], G [23:12], B [35:24], A [47:36]
//   srgb         the texture descriptor's format is srgba8
//   word [31:0]  result word, R in [7:0], G [15:8], B [23:16], A [31:24]
// Combinational.
module tfu_srgb_texel_encode (
  input  logic [47:0] c,
  input  logic        srgb,
  output logic [31:0] word
);
  logic [7:0] code [3];
  for (genvar k = 0; k < 3; k++) begin : g_rom
    tfu_srgb_encode_rom u_rom (.linear(c[12*k +: 12]), .code(code[k]));
    assign word[8*k +: 8] = srgb ? code[k] : c[12*k +: 8];
  end
  assign word[31:24] = c[43:36];
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3:0] unused_a_high;
  /* verilator lint_on UNUSEDSIGNAL */
  assign unused_a_high = c[47:44];
endmodule
