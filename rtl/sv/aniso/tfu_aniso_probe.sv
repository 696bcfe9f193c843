// Probe generator of anisotropic filtering: offset and weight of probe i of N along the major axis
// (EXT_texture_filter_anisotropic's u(x - 1/2 + i/(N+1), y); probes along the line of anisotropy as
// in Texram / Feline), from the generated probe ROM; bit-exact with tfu::probe_offset,
// tfu::dp::probe_offset_on_level and tfu::probe_rom (cmodel/aniso.hpp). The address generator
// presents one probe index per clock. Combinational.
//
// Ports:
//   major_du, major_dv      [31:0] signed  major derivative vector (tfu_aniso_lod), Q.16 level-0 texels
//   probes                  [4:0]          N, 1..16
//   index                   [4:0]          i, 1..N
//   level                   [3:0]          level L of the footprint (0..15)
//   off_du_q16, off_dv_q16  [30:0] signed  probe offset from the centre, Q.16 level-0 texels
//   off_du_q8, off_dv_q8    [22:0] signed  the same on level L, Q.8: added to the centre's
//                                          u = floor(s W_L 2^8) - 128 (dp::probe_texel_coord)
//   weight                  [8:0]          w(N, i) of the averaging unit (sum over i = 256)
module tfu_aniso_probe (
  input  logic signed [31:0] major_du,
  input  logic signed [31:0] major_dv,
  input  logic        [4:0]  probes,
  input  logic        [4:0]  index,
  input  logic        [3:0]  level,
  output logic signed [30:0] off_du_q16,
  output logic signed [30:0] off_dv_q16,
  output logic signed [22:0] off_du_q8,
  output logic signed [22:0] off_dv_q8,
  output logic        [8:0]  weight
);
  logic [24:0] word;  // {weight[8:0], frac_neg, frac_mag[14:0]}
  tfu_aniso_probe_rom u_rom (.addr({4'(probes - 5'd1), 4'(index - 5'd1)}), .data(word));
  assign weight = word[24:16];

  tfu_aniso_probe_axis u_du (.d(major_du), .frac_neg(word[15]), .frac_mag(word[14:0]), .level(level),
                             .off_q16(off_du_q16), .off_q8(off_du_q8));
  tfu_aniso_probe_axis u_dv (.d(major_dv), .frac_neg(word[15]), .frac_mag(word[14:0]), .level(level),
                             .off_q16(off_dv_q16), .off_q8(off_dv_q8));
endmodule
