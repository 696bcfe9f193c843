// log2 unit of the LOD unit (Pharr, GPU Gems ch. 25; GL 4.6 Eq. 8.4-8.6): log2(x) in Q.8 for the
// squared derivative length rho^2, bit-exact with tfu::log2_q8 of cmodel/lod.hpp. Combinational.
//
// Ports:
//   x       [63:0]         unsigned input (rho^2, Q.32 in the LOD unit; any 64-bit value)
//   log2_q8 [15:0] signed  (e << 8) + rom[index] for x >= 1, where e is the position of the leading
//                          one and index the 9 bits below it (x shifted left when e < 9: the bits
//                          below the leading one, zero-filled); -(64 << 8) = -16384 for x = 0
//                          (kLodMinusInfinity). Range -16384..16384.
//
// Leading-one detector and normaliser in one: six conditional shifts by 32, 16, 8, 4, 2, 1 move the
// leading one to bit 63; the shift amounts are the leading-zero count lz, and e = 63 - lz = ~lz.
// The 9 bits below the leading one then sit in bits [62:54] and address the generated 512 x 9-bit
// ROM tfu_log2_rom (rtl/sv/svgen.cpp from log2_rom()).
module tfu_log2_unit (
  input  logic [63:0]        x,
  output logic signed [15:0] log2_q8
);
  logic [63:0] s1, s2, s3, s4, s5, s6;
  logic        z5, z4, z3, z2, z1, z0;
  assign z5 = ~|x[63:32];
  assign s1 = z5 ? {x[31:0], 32'b0} : x;
  assign z4 = ~|s1[63:48];
  assign s2 = z4 ? {s1[47:0], 16'b0} : s1;
  assign z3 = ~|s2[63:56];
  assign s3 = z3 ? {s2[55:0], 8'b0} : s2;
  assign z2 = ~|s3[63:60];
  assign s4 = z2 ? {s3[59:0], 4'b0} : s3;
  assign z1 = ~|s4[63:62];
  assign s5 = z1 ? {s4[61:0], 2'b0} : s4;
  assign z0 = ~s5[63];
  assign s6 = z0 ? {s5[62:0], 1'b0} : s5;

  logic [5:0] lz;
  assign lz = {z5, z4, z3, z2, z1, z0};

  logic [8:0] frac;
  tfu_log2_rom u_rom (.addr(9'(s6 >> 54)), .data(frac));  // bits [62:54]; bit 63 is the leading one

  logic [5:0] e;
  assign e = ~lz;
  assign log2_q8 = (x == 64'd0) ? -16'sd16384 : $signed({2'b00, e, 8'b0} + {7'b0, frac});
endmodule
