// Probe count N of the anisotropic LOD unit on the footprint ellipse's axes: the smallest n with
// n (1 + t/8) Pmin' >= Pmax', i.e. n (8 + t) |D| >= 8 Pmax'^2 (Pmax' / Pmin' = Pmax'^2 / |D|,
// since Pmax' Pmin' = |D|), capped at maxAniso, optionally rounded up to a power of two; bit-exact
// with tfu::aniso_probe_count_ellipse (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   pmax2            [63:0]  Pmax'^2, Q.32 (tfu_aniso_ellipse_major)
//   det              [62:0]  |D| = |a x b|, Q.32 (tfu_aniso_dot_cross)
//   max_aniso        [4:0]   maxAniso, 1..16 (0 acts as 1, 17..31 as 16)
//   aniso_rounding           1: N rounded up to a power of two
//   aniso_threshold  [2:0]   t, 0..7 (0: n |D| >= Pmax'^2)
//   probes           [4:0]   N, 1..16
//
// The unit scales |D| once by 8 + t (a 63 x 4-bit product, 67 bits) and compares 8 Pmax'^2 (a
// shift, 67 bits) with all sixteen multiples n (8 + t) |D| (71 bits) at once: linear in n, the
// products share seven adders (3, 5, 7, 9, 11, 13, 15; the even ones are shifts). The compares form
// a thermometer code, so 1 + the number of failing compares is the count (17: none, e.g. |D| = 0 <
// Pmax'^2); tfu_aniso_cap_round caps and rounds it as for the screen axes.
module tfu_aniso_count_ellipse (
  input  logic [63:0] pmax2,
  input  logic [62:0] det,
  input  logic [4:0]  max_aniso,
  input  logic        aniso_rounding,
  input  logic [2:0]  aniso_threshold,
  output logic [4:0]  probes
);
  localparam int W = 71;  // 63 + 4 (8 + t) + 4 (n <= 16)
  logic [3:0] widen;      // 8 + t
  assign widen = 4'd8 + 4'(aniso_threshold);
  logic [W-1:0] x, p3, p5, p7, p9, p11, p13, p15;
  assign x   = W'(det) * W'(widen);
  assign p3  = (x << 1) + x;
  assign p5  = (x << 2) + x;
  assign p7  = (x << 3) - x;
  assign p9  = (x << 3) + x;
  assign p11 = (p5 << 1) + x;
  assign p13 = (p3 << 2) + x;
  assign p15 = (x << 4) - x;

  logic [W-1:0] mul [16];  // n (8 + t) |D| for n = 1..16 at index n - 1
  assign mul[0]  = x;
  assign mul[1]  = x << 1;
  assign mul[2]  = p3;
  assign mul[3]  = x << 2;
  assign mul[4]  = p5;
  assign mul[5]  = p3 << 1;
  assign mul[6]  = p7;
  assign mul[7]  = x << 3;
  assign mul[8]  = p9;
  assign mul[9]  = p5 << 1;
  assign mul[10] = p11;
  assign mul[11] = p3 << 2;
  assign mul[12] = p13;
  assign mul[13] = p7 << 1;
  assign mul[14] = p15;
  assign mul[15] = x << 4;

  logic [W-1:0] pmax2_8;  // 8 Pmax'^2
  assign pmax2_8 = W'(pmax2) << 3;
  logic [15:0] below;  // below[n - 1]: n (1 + t/8) Pmin' < Pmax'
  for (genvar k = 0; k < 16; k++) begin : g_cmp
    assign below[k] = mul[k] < pmax2_8;
  end

  logic [4:0] count;  // min(ceil(Pmax'^2 / ((1 + t/8) |D|)), 17)
  always_comb begin
    count = 5'd1;
    for (int k = 0; k < 16; k++) count = count + 5'(below[k]);
  end
  tfu_aniso_cap_round u_cap (.count(count), .max_aniso(max_aniso), .aniso_rounding(aniso_rounding), .probes(probes));
endmodule
