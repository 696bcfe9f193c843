// Radicand of the hypot unit (tfu_aniso_ellipse_major): M'^2 + m'^2 from the 16-bit mantissas, two
// 16 x 16-bit squares and a 33-bit sum; bit-exact with tfu::aniso_hypot (cmodel/aniso.hpp).
// Combinational.
//
// Ports:
//   big_m, little_m  [15:0]  M', m' (tfu_aniso_hypot_prep)
//   rad              [33:0]  M'^2 + m'^2 < 2^33, padded to an even width for the root's digit pairs
module tfu_aniso_hypot_square (
  input  logic [15:0] big_m,
  input  logic [15:0] little_m,
  output logic [33:0] rad
);
  assign rad = 34'(32'(big_m) * 32'(big_m)) + 34'(32'(little_m) * 32'(little_m));
endmodule
