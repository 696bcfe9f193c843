// Major-axis select of the anisotropic LOD unit (EXT_texture_filter_anisotropic: Pmax = max(Px, Py),
// Pmin = min(Px, Py); the probes step along the major axis's derivative vector); bit-exact with the
// select in tfu::aniso_lod (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   px2, py2                [62:0]         Px^2, Py^2, Q.32 (tfu_aniso_axis_len2)
//   mag_udx, mag_vdx        [30:0]         clamped |du/dx|, |dv/dx|
//   mag_udy, mag_vdy        [30:0]         clamped |du/dy|, |dv/dy|
//   neg_udx, neg_vdx, neg_udy, neg_vdy     signs of the four derivatives (1 = negative)
//   major_x                                Px^2 >= Py^2 (a tie goes to x)
//   pmax2, pmin2            [62:0]         Pmax^2, Pmin^2
//   major_du, major_dv      [31:0] signed  the major derivative vector: clamped magnitude with
//                                          the input's sign (a clamped -2^47 stays negative)
module tfu_aniso_major_select (
  input  logic        [62:0] px2,
  input  logic        [62:0] py2,
  input  logic        [30:0] mag_udx,
  input  logic        [30:0] mag_vdx,
  input  logic        [30:0] mag_udy,
  input  logic        [30:0] mag_vdy,
  input  logic               neg_udx,
  input  logic               neg_vdx,
  input  logic               neg_udy,
  input  logic               neg_vdy,
  output logic               major_x,
  output logic        [62:0] pmax2,
  output logic        [62:0] pmin2,
  output logic signed [31:0] major_du,
  output logic signed [31:0] major_dv
);
  assign major_x = px2 >= py2;
  assign pmax2 = major_x ? px2 : py2;
  assign pmin2 = major_x ? py2 : px2;

  logic [30:0] mag_du, mag_dv;
  logic        neg_du, neg_dv;
  assign mag_du = major_x ? mag_udx : mag_udy;
  assign mag_dv = major_x ? mag_vdx : mag_vdy;
  assign neg_du = major_x ? neg_udx : neg_udy;
  assign neg_dv = major_x ? neg_vdx : neg_vdy;
  assign major_du = neg_du ? -$signed({1'b0, mag_du}) : $signed({1'b0, mag_du});
  assign major_dv = neg_dv ? -$signed({1'b0, mag_dv}) : $signed({1'b0, mag_dv});
endmodule
