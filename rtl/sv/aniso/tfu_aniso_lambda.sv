// lambda of the anisotropic LOD unit (EXT_texture_filter_anisotropic: lambda' = log2(Pmax / N)),
// from Pmax^2 without a square root or divider: (log2_q8(Pmax^2) - 32 * 256 - R[N] + 1) >> 1 with
// R[N] = round(512 log2 N) from the generated 16-entry ROM tfu_aniso_log2sq_rom; bit-exact with
// tfu::aniso_lambda (cmodel/aniso.hpp), and with the isotropic LOD unit's lambda for N = 1
// (R[1] = 0). Combinational.
//
// Ports:
//   pmax2      [63:0]          Pmax^2 (screen axes, < 2^63) or Pmax'^2 (ellipse axes, < 2^64), Q.32
//                              level-0 texels^2
//   probes     [4:0]           N, 1..16
//   lambda_q8  [15:0] signed   log2(Pmax / N) in Q.8 before bias and clamp, -5120..4096;
//                              -16384 (kLodMinusInfinity) for Pmax^2 = 0
module tfu_aniso_lambda (
  input  logic        [63:0] pmax2,
  input  logic        [4:0]  probes,
  output logic signed [15:0] lambda_q8
);
  logic signed [15:0] log2_q8;
  tfu_log2_unit u_log2 (.x(pmax2), .log2_q8(log2_q8));

  logic [11:0] r;
  tfu_aniso_log2sq_rom u_rom (.addr(4'(probes - 5'd1)), .data(r));

  logic signed [16:0] l2;  // log2(Pmax^2 / N^2) in Q.8: -10240..8192
  assign l2 = $signed({log2_q8[15], log2_q8}) - 17'sd8192 - $signed({5'b0, r});
  logic signed [15:0] half;  // (l2 + 1) >> 1: halving, round half up; -5120..4096
  assign half = 16'((l2 + 17'sd1) >>> 1);
  assign lambda_q8 = (pmax2 == 64'd0) ? -16'sd16384 : half;
endmodule
