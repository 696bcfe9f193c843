// Last part of the footprint ellipse's major axis (tfu_aniso_ellipse_major): H = M + ((h - M') << s),
// 65 bits (h - M' < 2^15), then Pmax'^2 = (A + min(H, A)) >> 1 (H <= A in exact terms); bit-exact
// with the last steps of tfu::aniso_hypot and tfu::ellipse_major_len2 (cmodel/aniso.hpp).
// Combinational.
//
// Ports:
//   a      [63:0]  A = Px^2 + Py^2 (tfu_aniso_hypot_prep)
//   big    [63:0]  M = max(|E|, |F|)
//   s      [5:0]   the mantissa shift, 0..48
//   big_m  [15:0]  M' = M >> s
//   h      [16:0]  floor(sqrt(M'^2 + m'^2)) (tfu_aniso_hypot_root), M' <= h < M' + 2^15
//   pmax2  [63:0]  Pmax'^2, Q.32, <= A
module tfu_aniso_hypot_finish (
  input  logic [63:0] a,
  input  logic [63:0] big,
  input  logic [5:0]  s,
  input  logic [15:0] big_m,
  input  logic [16:0] h,
  output logic [63:0] pmax2
);
  logic [16:0] step;        // h - M' < 2^15
  assign step = h - 17'(big_m);
  logic [64:0] hyp, hyp_c;  // H, min(H, A)
  assign hyp = 65'(big) + (65'(step) << s);
  assign hyp_c = (hyp > 65'(a)) ? 65'(a) : hyp;
  assign pmax2 = 64'((65'(a) + hyp_c) >> 1);
endmodule
