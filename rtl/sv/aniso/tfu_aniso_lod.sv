// Anisotropic LOD unit (EXT_texture_filter_anisotropic, Sec. 3.8.5 as changed by the extension:
// Px, Py, Pmax, Pmin, N = min(ceil(Pmax / Pmin), maxAniso), lambda' = log2(Pmax / N)), in fixed
// point without square roots or dividers; with the descriptor's aniso_axes, on the footprint
// ellipse's true axes instead of the screen axes' Px, Py; bit-exact with tfu::aniso_lod
// (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   dudx, dvdx, dudy, dvdy  [48:0] signed  derivatives, Q.16 level-0 texels (lod.hpp TexelDerivatives)
//   max_aniso               [4:0]          maxAniso, 1..16 (0 acts as 1, 17..31 as 16)
//   aniso_rounding                         1: N rounded up to a power of two
//   aniso_threshold         [2:0]          probe threshold t, 0..7 (0: the spec's N; tfu_aniso_count)
//   aniso_axes                             0: Px, Py along the screen axes (the spec); 1: the
//                                          ellipse's axes Pmax', Pmin' (N from n |D|, lambda from Pmax'^2)
//   px2, py2                [62:0]         Px^2, Py^2, Q.32 (clamped magnitudes, lod.hpp)
//   major_x                                Px^2 >= Py^2: the probes step along (du/dx, dv/dx)
//   major_du, major_dv      [31:0] signed  the major derivative vector, magnitudes clamped to
//                                          2^31 - 1, signs kept (Q.16 level-0 texels)
//   probes                  [4:0]          N, 1..16
//   lambda_q8               [15:0] signed  log2(Pmax / N), Q.8, before bias/clamp (-16384 for Pmax = 0)
//   pmax2                   [63:0]         the squared major length lambda is formed from:
//                                          max(Px^2, Py^2) (screen axes) or Pmax'^2 (ellipse axes)
//   det                     [62:0]         |D| = |a x b| (ellipse axes; 0 with the screen axes)
//
// Parts, in series: two tfu_aniso_axis_len2 (the four squares, side by side),
// tfu_aniso_major_select (63-bit compare, Pmax/Pmin and major-vector select), tfu_aniso_count (N),
// tfu_aniso_lambda (log2 unit and the log2(N^2) ROM). Beside them for the ellipse axes:
// tfu_aniso_dot_cross (four 31 x 31-bit products, beside the squares), tfu_aniso_ellipse_major
// (the hypot, after the squares) and tfu_aniso_count_ellipse (N); aniso_axes selects N and the
// lambda unit's input.
module tfu_aniso_lod (
  input  logic signed [48:0] dudx,
  input  logic signed [48:0] dvdx,
  input  logic signed [48:0] dudy,
  input  logic signed [48:0] dvdy,
  input  logic        [4:0]  max_aniso,
  input  logic               aniso_rounding,
  input  logic        [2:0]  aniso_threshold,
  input  logic               aniso_axes,
  output logic        [62:0] px2,
  output logic        [62:0] py2,
  output logic               major_x,
  output logic signed [31:0] major_du,
  output logic signed [31:0] major_dv,
  output logic        [4:0]  probes,
  output logic signed [15:0] lambda_q8,
  output logic        [63:0] pmax2,
  output logic        [62:0] det
);
  logic [30:0] mag_udx, mag_vdx, mag_udy, mag_vdy;
  tfu_aniso_axis_len2 u_px (.du(dudx), .dv(dvdx), .mag_u(mag_udx), .mag_v(mag_vdx), .len2(px2));
  tfu_aniso_axis_len2 u_py (.du(dudy), .dv(dvdy), .mag_u(mag_udy), .mag_v(mag_vdy), .len2(py2));

  logic [62:0] scr_pmax2, scr_pmin2;
  tfu_aniso_major_select u_select (
    .px2(px2), .py2(py2), .mag_udx(mag_udx), .mag_vdx(mag_vdx), .mag_udy(mag_udy), .mag_vdy(mag_vdy),
    .neg_udx(dudx[48]), .neg_vdx(dvdx[48]), .neg_udy(dudy[48]), .neg_vdy(dvdy[48]),
    .major_x(major_x), .pmax2(scr_pmax2), .pmin2(scr_pmin2), .major_du(major_du), .major_dv(major_dv));

  logic [4:0] scr_probes;
  tfu_aniso_count u_count (.pmax2(scr_pmax2), .pmin2(scr_pmin2), .max_aniso(max_aniso), .aniso_rounding(aniso_rounding),
                           .aniso_threshold(aniso_threshold), .probes(scr_probes));

  logic signed [63:0] dot, det_s;
  tfu_aniso_dot_cross u_dot_cross (
    .mag_udx(mag_udx), .mag_vdx(mag_vdx), .mag_udy(mag_udy), .mag_vdy(mag_vdy),
    .neg_udx(dudx[48]), .neg_vdx(dvdx[48]), .neg_udy(dudy[48]), .neg_vdy(dvdy[48]), .dot(dot), .det(det_s));
  logic [63:0] ell_pmax2;
  logic [62:0] det_mag;
  tfu_aniso_ellipse_major u_ellipse (.px2(px2), .py2(py2), .dot(dot), .pmax2(ell_pmax2));
  assign det_mag = det_s[63] ? 63'(-det_s) : 63'(det_s);  // |D| < 2^63
  logic [4:0] ell_probes;
  tfu_aniso_count_ellipse u_count_ellipse (.pmax2(ell_pmax2), .det(det_mag), .max_aniso(max_aniso),
                                           .aniso_rounding(aniso_rounding), .aniso_threshold(aniso_threshold),
                                           .probes(ell_probes));

  assign probes = aniso_axes ? ell_probes : scr_probes;
  assign pmax2 = aniso_axes ? ell_pmax2 : 64'(scr_pmax2);
  assign det = aniso_axes ? det_mag : 63'd0;
  tfu_aniso_lambda u_lambda (.pmax2(pmax2), .probes(probes), .lambda_q8(lambda_q8));
endmodule
