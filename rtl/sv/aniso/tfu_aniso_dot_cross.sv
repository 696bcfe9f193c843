// Dot and cross product of the two derivative vectors a = (du/dx, dv/dx), b = (du/dy, dv/dy) for
// the footprint ellipse's axes (Heckbert 1989; docs/anisotropic.md, "Lambda against the angle"):
// a.b and D = a x b, exact; bit-exact with tfu::aniso_dot_cross (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   mag_udx, mag_vdx, mag_udy, mag_vdy  [30:0]         |du/dx|, |dv/dx|, |du/dy|, |dv/dy| clamped to
//                                                      2^31 - 1 (from tfu_aniso_axis_len2)
//   neg_udx, neg_vdx, neg_udy, neg_vdy                 the derivatives' signs (the input's bit 48)
//   dot                                 [63:0] signed  a.b = du/dx du/dy + dv/dx dv/dy, Q.32, |dot| < 2^63
//   det                                 [63:0] signed  D = du/dx dv/dy - dv/dx du/dy, Q.32, |det| < 2^63
//
// Four 31 x 31-bit unsigned products (< 2^62 each), signed by the XOR of their factors' signs,
// and one 64-bit adder per output.
module tfu_aniso_dot_cross (
  input  logic        [30:0] mag_udx,
  input  logic        [30:0] mag_vdx,
  input  logic        [30:0] mag_udy,
  input  logic        [30:0] mag_vdy,
  input  logic               neg_udx,
  input  logic               neg_vdx,
  input  logic               neg_udy,
  input  logic               neg_vdy,
  output logic signed [63:0] dot,
  output logic signed [63:0] det
);
  logic [61:0] p_uu, p_vv, p_uv, p_vu;  // du/dx du/dy, dv/dx dv/dy, du/dx dv/dy, dv/dx du/dy
  assign p_uu = 62'(mag_udx) * 62'(mag_udy);
  assign p_vv = 62'(mag_vdx) * 62'(mag_vdy);
  assign p_uv = 62'(mag_udx) * 62'(mag_vdy);
  assign p_vu = 62'(mag_vdx) * 62'(mag_udy);

  logic signed [63:0] s_uu, s_vv, s_uv, s_vu;
  assign s_uu = (neg_udx ^ neg_udy) ? -$signed({2'b0, p_uu}) : $signed({2'b0, p_uu});
  assign s_vv = (neg_vdx ^ neg_vdy) ? -$signed({2'b0, p_vv}) : $signed({2'b0, p_vv});
  assign s_uv = (neg_udx ^ neg_vdy) ? -$signed({2'b0, p_uv}) : $signed({2'b0, p_uv});
  assign s_vu = (neg_vdx ^ neg_udy) ? -$signed({2'b0, p_vu}) : $signed({2'b0, p_vu});
  assign dot = s_uu + s_vv;
  assign det = s_uv - s_vu;
endmodule
