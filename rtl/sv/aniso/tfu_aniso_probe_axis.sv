// One component of a probe offset (EXT_texture_filter_anisotropic: the probe of pixel position
// x - 1/2 + i/(N+1) along the major axis, i.e. d (2i - N - 1) / (2 (N + 1)) texels from the centre)
// and its Q.8 value on level L; bit-exact with tfu::probe_offset_q16 and
// tfu::dp::probe_offset_on_level (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   d          [31:0] signed  major derivative component, Q.16 level-0 texels, |d| <= 2^31 - 1
//   frac_neg                  sign of the probe fraction q(N, i) (1 = negative)
//   frac_mag   [14:0]         |q(N, i)|, Q.16 (<= 28,913)
//   level      [3:0]          level L of the probe's footprint, 0..15
//   off_q16    [30:0] signed  sgn ((|d| |q| + 2^15) >> 16): level-0 texels, Q.16, |.| < 2^30
//   off_q8     [22:0] signed  sgn ((|off| + 2^(7 + L)) >> (8 + L)): Q.8 texels of level L
//
// Sign-magnitude throughout (round half away from zero): the probe set stays exactly symmetric
// about the centre. One 31 x 15-bit multiplier.
module tfu_aniso_probe_axis (
  input  logic signed [31:0] d,
  input  logic               frac_neg,
  input  logic        [14:0] frac_mag,
  input  logic        [3:0]  level,
  output logic signed [30:0] off_q16,
  output logic signed [22:0] off_q8
);
  logic [30:0] mag_d;
  assign mag_d = d[31] ? 31'(-d) : d[30:0];

  logic [45:0] prod;
  assign prod = 46'(mag_d) * 46'(frac_mag);
  logic [29:0] m16;  // |offset|, Q.16 (the product is < 2^46 - 2^15: the sum does not carry out)
  assign m16 = 30'((prod + 46'd32768) >> 16);

  logic neg;
  assign neg = d[31] ^ frac_neg;
  assign off_q16 = neg ? -$signed({1'b0, m16}) : $signed({1'b0, m16});

  logic [30:0] biased;
  assign biased = {1'b0, m16} + (31'd128 << level);
  logic [21:0] ml;  // |offset| on level L, Q.8 (< 2^22)
  assign ml = 22'(biased >> (5'd8 + 5'(level)));
  assign off_q8 = neg ? -$signed({1'b0, ml}) : $signed({1'b0, ml});
endmodule
