// Squared axis length of the anisotropic LOD unit: Px^2 = (du/dx)^2 + (dv/dx)^2 of the
// EXT_texture_filter_anisotropic reference (likewise Py^2), without the square root; bit-exact with
// tfu::derivative_magnitude and tfu::derivative_length_sq (cmodel/lod.hpp). Combinational.
//
// Ports:
//   du, dv        [48:0] signed  derivative components, Q.16 level-0 texels (the input stage's
//                                float_to_fixed values saturate at +-2^46; a quad difference of two
//                                of them needs 49 bits)
//   mag_u, mag_v  [30:0]         |du|, |dv| clamped to 2^31 - 1 (kDerivativeClamp)
//   len2          [62:0]         mag_u^2 + mag_v^2, Q.32 (< 2^63)
//
// Each square is summed from its symmetric partial products,
//   x^2 = sum_k x_k 4^k + sum_k x_k (x >> (k + 1)) 2^(2k + 2),
// 496 product bits instead of the 961 of a general 31 x 31 multiplier; the diagonal terms of both
// squares are one vector each (no adder), and both squares share one addition.
module tfu_aniso_axis_len2 (
  input  logic signed [48:0] du,
  input  logic signed [48:0] dv,
  output logic        [30:0] mag_u,
  output logic        [30:0] mag_v,
  output logic        [62:0] len2
);
  logic [48:0] abs_u, abs_v;
  assign abs_u = du[48] ? 49'(-du) : 49'(du);  // -(-2^48) = 2^48 as unsigned: still the magnitude
  assign abs_v = dv[48] ? 49'(-dv) : 49'(dv);
  assign mag_u = (|abs_u[48:31]) ? 31'h7fff_ffff : abs_u[30:0];
  assign mag_v = (|abs_v[48:31]) ? 31'h7fff_ffff : abs_v[30:0];

  logic [62:0] diag_u, diag_v;  // sum_k x_k 4^k
  always_comb begin
    diag_u = '0;
    diag_v = '0;
    for (int k = 0; k < 31; k++) begin
      diag_u[2 * k] = mag_u[k];
      diag_v[2 * k] = mag_v[k];
    end
  end

  logic [62:0] row_u [30];  // x_k (x >> (k + 1)) 2^(2k + 2), k = 0..29 (row 30 is empty)
  logic [62:0] row_v [30];
  for (genvar k = 0; k < 30; k++) begin : g_rows
    assign row_u[k] = mag_u[k] ? ((63'(mag_u) >> (k + 1)) << (2 * k + 2)) : 63'd0;
    assign row_v[k] = mag_v[k] ? ((63'(mag_v) >> (k + 1)) << (2 * k + 2)) : 63'd0;
  end

  always_comb begin
    len2 = diag_u + diag_v;
    for (int k = 0; k < 30; k++) len2 = len2 + row_u[k] + row_v[k];
  end
endmodule
