// First part of the footprint ellipse's major axis (tfu_aniso_ellipse_major): A = Px^2 + Py^2, the
// hypot's operands |E| = |Px^2 - Py^2| and |F| = 2 |a.b|, M = max(|E|, |F|), m = min, the mantissa
// shift s = max(0, msb(M) - 15) from a leading-one detector and the 16-bit mantissas M' = M >> s,
// m' = m >> s (truncated); bit-exact with the first steps of tfu::aniso_hypot and
// tfu::ellipse_major_len2 (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   px2, py2  [62:0]         Px^2, Py^2, Q.32 (tfu_aniso_axis_len2)
//   dot       [63:0] signed  a.b, Q.32 (tfu_aniso_dot_cross), |dot| < 2^63
//   a         [63:0]         A = Px^2 + Py^2 < 2^64
//   big       [63:0]         M = max(|E|, |F|) (|E| < 2^63, |F| < 2^64)
//   s         [5:0]          max(0, msb(M) - 15), 0..48
//   big_m     [15:0]         M' = M >> s
//   little_m  [15:0]         m' = min(|E|, |F|) >> s
module tfu_aniso_hypot_prep (
  input  logic        [62:0] px2,
  input  logic        [62:0] py2,
  input  logic signed [63:0] dot,
  output logic        [63:0] a,
  output logic        [63:0] big,
  output logic        [5:0]  s,
  output logic        [15:0] big_m,
  output logic        [15:0] little_m
);
  assign a = 64'(px2) + 64'(py2);
  logic [62:0] e;  // |E|
  assign e = (px2 >= py2) ? px2 - py2 : py2 - px2;
  logic [62:0] dot_mag;  // |a.b| < 2^63
  logic [63:0] f;        // |F| = 2 |a.b|
  assign dot_mag = dot[63] ? 63'(-dot) : 63'(dot);
  assign f = {dot_mag, 1'b0};

  logic [63:0] little;
  assign big = (64'(e) >= f) ? 64'(e) : f;
  assign little = (64'(e) >= f) ? f : 64'(e);

  always_comb begin
    s = 6'd0;
    for (int k = 16; k < 64; k++)
      if (big[k]) s = 6'(k - 15);
  end
  assign big_m = 16'(big >> s);
  assign little_m = 16'(little >> s);
endmodule
