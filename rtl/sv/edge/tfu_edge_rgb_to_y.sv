// RGB -> Y of the median ordering (Lee & Jen 2003 Sec. 6: "a carry-save adder tree"), RGBA8:
//   y = 5 r + 9 g + 2 b = (r << 2) + r + (g << 3) + g + (b << 1)     0..4080
// as lee_jen::edge_luma (cmodel/edge_filter.hpp). VS16X2 (Y = ch0 + ch1) is not in the SV.
//
// Ports:
//   r, g, b [7:0]   colour channels (alpha takes no part)
//   y       [11:0]  luma, unsigned
//
// Structure: five shifted terms, three levels of 3:2 carry-save adders (full adders per bit, no
// carry propagation), then one 12-bit carry-propagate adder. Every sum is taken modulo 2^12, which
// is exact because y < 2^12. Combinational.
module tfu_edge_rgb_to_y (
  input  logic [7:0]  r,
  input  logic [7:0]  g,
  input  logic [7:0]  b,
  output logic [11:0] y
);
  logic [11:0] t0, t1, t2, t3, t4;
  assign t0 = {2'b00, r, 2'b00};   // 4 r
  assign t1 = {4'b0000, r};        // r
  assign t2 = {1'b0, g, 3'b000};   // 8 g
  assign t3 = {4'b0000, g};        // g
  assign t4 = {3'b000, b, 1'b0};   // 2 b

  // 3:2 compressor: x + y + z = s + c (c already shifted left by one; the carry out of bit 11 is
  // dropped, which is exact modulo 2^12).
  logic [11:0] s1, c1, s2, c2, s3, c3;
  assign s1 = t0 ^ t1 ^ t2;
  assign c1 = {(t0[10:0] & t1[10:0]) | (t0[10:0] & t2[10:0]) | (t1[10:0] & t2[10:0]), 1'b0};
  assign s2 = s1 ^ c1 ^ t3;
  assign c2 = {(s1[10:0] & c1[10:0]) | (s1[10:0] & t3[10:0]) | (c1[10:0] & t3[10:0]), 1'b0};
  assign s3 = s2 ^ c2 ^ t4;
  assign c3 = {(s2[10:0] & c2[10:0]) | (s2[10:0] & t4[10:0]) | (c2[10:0] & t4[10:0]), 1'b0};

  assign y = s3 + c3;  // carry-propagate adder
endmodule
