// Cubic weight stage (Hadwiger et al. 2002 Sec. 2; Hadwiger 2004 Sec. 3.1-3.2): the 4 x 4 2D
// weights of the separable tiled-ROM filter, bit-exact with tfu::dp::tile_weights_2d (cmodel/
// datapath.hpp, sampler.cpp) with nearest reconstruction and the default CUBIC ROM. Combinational.
//
// Ports (sizes from the generated package tfu_cubic_pkg, gen/tfu_cubic_pkg.sv):
//   fu, fv [7:0]            subtexel fractions (Q.8)
//   w  [16*tfu_cubic_pkg::W2_BITS-1:0]     2D weights, two's complement, scale M = 2^ROM_BITS - 1; tap (i, j)
//                           (texel offsets i + FIRST_TAP, j + FIRST_TAP) in word 4 j + i, i.e.
//                           bits [tfu_cubic_pkg::W2_BITS (4j+i) +: tfu_cubic_pkg::W2_BITS]
//
// Two reads of the interleaved ROM tfu_tile_rom (address f >> ROM_ADDR_SHIFT = nearest_address),
// 15 tile-weight multipliers, and for the tap at offset (0, 0) the complement M - sum(others), so
// the 16 weights sum to exactly M (one subtractor instead of a renormalising divider).
module tfu_cubic_weights (
  input  logic [7:0]              fu,
  input  logic [7:0]              fv,
  output logic [16*tfu_cubic_pkg::W2_BITS-1:0] w
);
  localparam int FIRST_TAP = tfu_cubic_pkg::FIRST_TAP;
  localparam int ROM_BITS = tfu_cubic_pkg::ROM_BITS;
  localparam int ROM_ADDR_BITS = tfu_cubic_pkg::ROM_ADDR_BITS;
  localparam int ROM_ADDR_SHIFT = tfu_cubic_pkg::ROM_ADDR_SHIFT;
  localparam int W2_BITS = tfu_cubic_pkg::W2_BITS;
  localparam int WB = ROM_BITS + 1;            // ROM word: sign + magnitude
  localparam int CENTRE = -FIRST_TAP;          // tap index of texel offset 0
  localparam int SB = WB + 4;                  // sum of 15 WB-bit products: no overflow

  logic [4*WB-1:0] row_x, row_y;
  tfu_tile_rom u_rom_x (.addr(ROM_ADDR_BITS'(fu >> ROM_ADDR_SHIFT)), .row(row_x));
  tfu_tile_rom u_rom_y (.addr(ROM_ADDR_BITS'(fv >> ROM_ADDR_SHIFT)), .row(row_y));

  logic signed [WB-1:0] p [16];
  for (genvar j = 0; j < 4; j++) begin : g_y
    for (genvar i = 0; i < 4; i++) begin : g_x
      if (i == CENTRE && j == CENTRE) begin : g_c
        assign p[4*j+i] = '0;
      end else begin : g_m
        tfu_tile_weight_mul #(.B(ROM_BITS)) u_mul (
          .wx(row_x[WB*i +: WB]), .wy(row_y[WB*j +: WB]), .w(p[4*j+i]));
      end
    end
  end

  logic signed [SB-1:0]      sum;
  logic signed [W2_BITS-1:0] centre;  // M - sum fits W2_BITS (generator-checked range)
  always_comb begin
    sum = '0;
    for (int k = 0; k < 16; k++) sum = sum + SB'(p[k]);
    centre = W2_BITS'(SB'((1 << ROM_BITS) - 1) - sum);
  end

  for (genvar k = 0; k < 16; k++) begin : g_out
    if (k == 4*CENTRE + CENTRE) begin : g_c
      assign w[W2_BITS*k +: W2_BITS] = centre;
    end else begin : g_m
      assign w[W2_BITS*k +: W2_BITS] = W2_BITS'(p[k]);
    end
  end
endmodule
