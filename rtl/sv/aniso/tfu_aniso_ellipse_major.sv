// Squared major axis of the footprint ellipse, Pmax'^2 = (A + H) / 2 with A = Px^2 + Py^2 and
// H = sqrt(E^2 + F^2), E = Px^2 - Py^2, F = 2 a.b (Heckbert 1989; docs/anisotropic.md, "Lambda
// against the angle"), without a full-width root; bit-exact with tfu::ellipse_major_len2 and
// tfu::aniso_hypot (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   px2, py2  [62:0]         Px^2, Py^2, Q.32 (tfu_aniso_axis_len2)
//   dot       [63:0] signed  a.b, Q.32 (tfu_aniso_dot_cross), |dot| < 2^63
//   pmax2     [63:0]         Pmax'^2 = (A + min(H, A)) >> 1, Q.32, <= A < 2^64
//
// The hypot: M = max(|E|, |F|), m = min (|E| < 2^63, |F| = 2 |a.b| < 2^64); s = max(0, msb(M) - 15)
// from a leading-one detector (0..48); 16-bit mantissas M' = M >> s, m' = m >> s (truncated); the
// 33-bit radicand M'^2 + m'^2 (two 16 x 16-bit squares) and its 17-bit floor root h, digit by
// digit (17 compare-subtract stages); H = M + ((h - M') << s), 65 bits (h - M' < 2^15). H is exact
// when E or F is 0, and within 2.5 * 2^s of the true hypot. Then min(H, A) (H <= A in exact
// terms), a 65-bit sum and a shift.
//
// Four parts in series, each its own module so that the gate count maps them one by one (the
// flattened block does not finish in ABC; docs/silicon.md, composites): tfu_aniso_hypot_prep (A,
// |E|, |F|, M, m, s, the mantissas), tfu_aniso_hypot_square (the radicand), tfu_aniso_hypot_root
// (h) and tfu_aniso_hypot_finish (H, min(H, A), Pmax'^2).
module tfu_aniso_ellipse_major (
  input  logic        [62:0] px2,
  input  logic        [62:0] py2,
  input  logic signed [63:0] dot,
  output logic        [63:0] pmax2
);
  logic [63:0] a, big;
  logic [5:0]  s;
  logic [15:0] big_m, little_m;
  logic [33:0] rad;
  logic [16:0] h;
  tfu_aniso_hypot_prep u_prep (.px2(px2), .py2(py2), .dot(dot), .a(a), .big(big), .s(s), .big_m(big_m),
                               .little_m(little_m));
  tfu_aniso_hypot_square u_square (.big_m(big_m), .little_m(little_m), .rad(rad));
  tfu_aniso_hypot_root u_root (.rad(rad), .h(h));
  tfu_aniso_hypot_finish u_finish (.a(a), .big(big), .s(s), .big_m(big_m), .h(h), .pmax2(pmax2));
endmodule
