// Probe count N of the anisotropic LOD unit (EXT_texture_filter_anisotropic:
// N = min(ceil(Pmax / Pmin), maxAniso), optionally rounded up to a power of two), exactly and
// without a divider or square root, with the descriptor's probe threshold t (N = min(ceil(Pmax /
// ((1 + t/8) Pmin)), maxAniso); t = 0 the spec's N); bit-exact with tfu::aniso_probe_count
// (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   pmax2      [62:0]  Pmax^2 = max(Px^2, Py^2), Q.32
//   pmin2      [62:0]  Pmin^2 = min(Px^2, Py^2), Q.32 (pmin2 <= pmax2)
//   max_aniso  [4:0]   maxAniso of the sampler descriptor, 1..16 (0 acts as 1, 17..31 as 16)
//   aniso_rounding     1: N rounded up to a power of two (the spec's "nearest supported rate")
//   aniso_threshold [2:0] t, 0..7: a probe may cover (1 + t/8) Pmin (docs/anisotropic.md)
//   probes     [4:0]   N, 1..16
//
// ceil(Pmax / ((1 + t/8) Pmin)) is the smallest k >= 1 with k^2 (8 + t)^2 Pmin^2 >= 64 Pmax^2.
// The unit scales Pmin^2 once by (8 + t)^2 (64..225, 8 bits: a 63 x 8-bit product, 71 bits) and
// compares 64 Pmax^2 with all sixteen k^2 (8 + t)^2 Pmin^2 (79 bits) at once; the results form a
// thermometer code (the products grow with k), so 1 + the number of failing compares is
// min(ceil(.), 17) (17: none, e.g. Pmin = 0 < Pmax). With t = 0 the scale is 64, a shift matched
// by the shift of Pmax^2: the spec's k^2 Pmin^2 >= Pmax^2. The products share their adders: nine
// adders for the 16 constants (3, 7, 9, 25, 49, 81, 121, 169, 225; the rest are shifts of these).
// tfu_aniso_cap_round caps the count at maxAniso and rounds it.
module tfu_aniso_count (
  input  logic [62:0] pmax2,
  input  logic [62:0] pmin2,
  input  logic [4:0]  max_aniso,
  input  logic        aniso_rounding,
  input  logic [2:0]  aniso_threshold,
  output logic [4:0]  probes
);
  localparam int W = 79;  // 63 + 8 (threshold scale) + log2(256) (k^2)
  logic [3:0] widen;      // 8 + t
  logic [7:0] scale;      // (8 + t)^2
  assign widen = 4'd8 + 4'(aniso_threshold);
  assign scale = 8'(widen * widen);
  logic [W-1:0] x, p3, p7, p9, p25, p49, p81, p121, p169, p225;
  assign x    = W'(pmin2) * W'(scale);
  assign p3   = (x << 1) + x;
  assign p7   = (x << 3) - x;
  assign p9   = (p3 << 1) + p3;
  assign p25  = (x << 4) + p9;
  assign p49  = (p3 << 4) + x;
  assign p81  = (p9 << 3) + p9;
  assign p121 = (x << 7) - p7;
  assign p169 = (p9 << 4) + p25;
  assign p225 = (p9 << 4) + p81;

  logic [W-1:0] sq [16];  // k^2 (8 + t)^2 Pmin^2 for k = 1..16 at index k - 1
  assign sq[0]  = x;
  assign sq[1]  = x << 2;
  assign sq[2]  = p9;
  assign sq[3]  = x << 4;
  assign sq[4]  = p25;
  assign sq[5]  = p9 << 2;
  assign sq[6]  = p49;
  assign sq[7]  = x << 6;
  assign sq[8]  = p81;
  assign sq[9]  = p25 << 2;
  assign sq[10] = p121;
  assign sq[11] = p9 << 4;
  assign sq[12] = p169;
  assign sq[13] = p49 << 2;
  assign sq[14] = p225;
  assign sq[15] = x << 8;

  logic [W-1:0] pmax2_64;  // 64 Pmax^2
  assign pmax2_64 = W'(pmax2) << 6;
  logic [15:0] below;  // below[k - 1]: k (1 + t/8) Pmin < Pmax
  for (genvar k = 0; k < 16; k++) begin : g_cmp
    assign below[k] = sq[k] < pmax2_64;
  end

  logic [4:0] ratio_ceil;  // min(ceil(Pmax / ((1 + t/8) Pmin)), 17)
  always_comb begin
    ratio_ceil = 5'd1;
    for (int k = 0; k < 16; k++) ratio_ceil = ratio_ceil + 5'(below[k]);
  end

  tfu_aniso_cap_round u_cap (.count(ratio_ceil), .max_aniso(max_aniso), .aniso_rounding(aniso_rounding), .probes(probes));
endmodule
