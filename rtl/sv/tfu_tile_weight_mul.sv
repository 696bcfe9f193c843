// Tile-weight multiplier (Hadwiger et al. 2002 Sec. 2: separable composition w(x, y) = wx wy of
// tiled 1D weights; Hadwiger 2004 Sec. 3.5, Eq. 3.7 and the division-free form). Bit-exact with
// tfu::tile_weight_multiply of cmodel/weight_rom.hpp (unorm::mul_divfree). Combinational.
//
// Parameter B: magnitude bits b of the ROM words (1.0 <-> M = 2^B - 1); default 8.
// Ports:
//   wx, wy [B:0]         sign-magnitude ROM words (cmodel/rom_dump.hpp): [B] = sign (1 = negative),
//                        [B-1:0] = magnitude
//   w      [B:0] signed  two's-complement product: +/- mul_divfree(|wx|, |wy|), sign = sx ^ sy;
//                        mul_divfree: i = x y + 2^(B-1); (i + (i >> B)) >> B == round(x y / M)
module tfu_tile_weight_mul #(
  parameter int B = 8
) (
  input  logic [B:0]        wx,
  input  logic [B:0]        wy,
  output logic signed [B:0] w
);
  logic [2*B-1:0] i;    // x y + 2^(B-1) < 2^(2B)
  logic [2*B:0]   t;    // i + (i >> B)
  logic [B-1:0]   mag;  // <= M
  assign i   = wx[B-1:0] * wy[B-1:0] + (2*B)'(1 << (B - 1));
  assign t   = {1'b0, i} + {{(B+1){1'b0}}, i[2*B-1:B]};
  assign mag = B'(t >> B);
  assign w   = (wx[B] ^ wy[B]) ? -$signed({1'b0, mag}) : $signed({1'b0, mag});
endmodule
