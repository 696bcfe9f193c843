// Anisotropic LOD unit (EXT_texture_filter_anisotropic, Sec. 3.8.5 as changed by the extension:
// Px, Py, Pmax, Pmin, N = min(ceil(Pmax / Pmin), maxAniso), lambda' = log2(Pmax / N)), in fixed
// point without square roots or dividers; bit-exact with tfu::aniso_lod (cmodel/aniso.hpp).
// Combinational.
//
// Ports:
//   dudx, dvdx, dudy, dvdy  [48:0] signed  derivatives, Q.16 level-0 texels (lod.hpp TexelDerivatives)
//   max_aniso               [4:0]          maxAniso, 1..16 (0 acts as 1, 17..31 as 16)
//   aniso_rounding                         1: N rounded up to a power of two
//   aniso_threshold         [2:0]          probe threshold t, 0..7 (0: the spec's N; tfu_aniso_count)
//   px2, py2                [62:0]         Px^2, Py^2, Q.32 (clamped magnitudes, lod.hpp)
//   major_x                                Px^2 >= Py^2: the probes step along (du/dx, dv/dx)
//   major_du, major_dv      [31:0] signed  the major derivative vector, magnitudes clamped to
//                                          2^31 - 1, signs kept (Q.16 level-0 texels)
//   probes                  [4:0]          N, 1..16
//   lambda_q8               [15:0] signed  log2(Pmax / N), Q.8, before bias/clamp (-16384 for Pmax = 0)
//
// Parts, in series: two tfu_aniso_axis_len2 (the four squares, side by side),
// tfu_aniso_major_select (63-bit compare, Pmax/Pmin and major-vector select), tfu_aniso_count (N),
// tfu_aniso_lambda (log2 unit and the log2(N^2) ROM).
module tfu_aniso_lod (
  input  logic signed [48:0] dudx,
  input  logic signed [48:0] dvdx,
  input  logic signed [48:0] dudy,
  input  logic signed [48:0] dvdy,
  input  logic        [4:0]  max_aniso,
  input  logic               aniso_rounding,
  input  logic        [2:0]  aniso_threshold,
  output logic        [62:0] px2,
  output logic        [62:0] py2,
  output logic               major_x,
  output logic signed [31:0] major_du,
  output logic signed [31:0] major_dv,
  output logic        [4:0]  probes,
  output logic signed [15:0] lambda_q8
);
  logic [30:0] mag_udx, mag_vdx, mag_udy, mag_vdy;
  tfu_aniso_axis_len2 u_px (.du(dudx), .dv(dvdx), .mag_u(mag_udx), .mag_v(mag_vdx), .len2(px2));
  tfu_aniso_axis_len2 u_py (.du(dudy), .dv(dvdy), .mag_u(mag_udy), .mag_v(mag_vdy), .len2(py2));

  logic [62:0] pmax2, pmin2;
  tfu_aniso_major_select u_select (
    .px2(px2), .py2(py2), .mag_udx(mag_udx), .mag_vdx(mag_vdx), .mag_udy(mag_udy), .mag_vdy(mag_vdy),
    .neg_udx(dudx[48]), .neg_vdx(dvdx[48]), .neg_udy(dudy[48]), .neg_vdy(dvdy[48]),
    .major_x(major_x), .pmax2(pmax2), .pmin2(pmin2), .major_du(major_du), .major_dv(major_dv));

  tfu_aniso_count u_count (.pmax2(pmax2), .pmin2(pmin2), .max_aniso(max_aniso), .aniso_rounding(aniso_rounding),
                           .aniso_threshold(aniso_threshold), .probes(probes));
  tfu_aniso_lambda u_lambda (.pmax2(pmax2), .probes(probes), .lambda_q8(lambda_q8));
endmodule
