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
module tfu_aniso_ellipse_major (
  input  logic        [62:0] px2,
  input  logic        [62:0] py2,
  input  logic signed [63:0] dot,
  output logic        [63:0] pmax2
);
  logic [63:0] a;  // A = Px^2 + Py^2 < 2^64
  assign a = 64'(px2) + 64'(py2);
  logic [62:0] e;  // |E|
  assign e = (px2 >= py2) ? px2 - py2 : py2 - px2;
  logic [62:0] dot_mag;  // |a.b| < 2^63
  logic [63:0] f;        // |F| = 2 |a.b|
  assign dot_mag = dot[63] ? 63'(-dot) : 63'(dot);
  assign f = {dot_mag, 1'b0};

  logic [63:0] big, little;
  assign big = (64'(e) >= f) ? 64'(e) : f;
  assign little = (64'(e) >= f) ? f : 64'(e);

  logic [5:0] s;  // max(0, msb(big) - 15)
  always_comb begin
    s = 6'd0;
    for (int k = 16; k < 64; k++)
      if (big[k]) s = 6'(k - 15);
  end
  logic [15:0] big_m, little_m;
  assign big_m = 16'(big >> s);
  assign little_m = 16'(little >> s);
  logic [33:0] rad;  // M'^2 + m'^2 < 2^33, padded to an even width
  assign rad = 34'(32'(big_m) * 32'(big_m)) + 34'(32'(little_m) * 32'(little_m));

  logic [16:0] h;  // floor(sqrt(rad)), restoring digit by digit: two radicand bits per stage
  always_comb begin
    logic [19:0] rem;
    logic [18:0] trial;
    rem = '0;
    h = '0;
    for (int i = 16; i >= 0; i--) begin
      rem = {rem[17:0], rad[2 * i + 1], rad[2 * i]};
      trial = {h, 2'b01};  // 4 root + 1
      if (rem >= 20'(trial)) begin
        rem = rem - 20'(trial);
        h = {h[15:0], 1'b1};
      end else begin
        h = {h[15:0], 1'b0};
      end
    end
  end

  logic [16:0] step;         // h - M' < 2^15
  assign step = h - 17'(big_m);
  logic [64:0] hyp, hyp_c;  // H, min(H, A)
  assign hyp = 65'(big) + (65'(step) << s);
  assign hyp_c = (hyp > 65'(a)) ? 65'(a) : hyp;
  assign pmax2 = 64'((65'(a) + hyp_c) >> 1);
endmodule
