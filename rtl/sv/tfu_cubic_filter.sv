// Cubic (4 x 4 tiled-ROM) filter for 8-bit RGBA texels (Hadwiger et al. 2002 Sec. 2; Hadwiger 2004
// Sec. 3.1-3.2, 3.5), bit-exact with the CUBIC path of tfu::Sampler::sample_level_filter
// (cmodel/sampler.cpp: dp::tile_weights_2d, filter_tiled_acc, floor_div(2 acc + M, 2 M), clamp)
// for the default ROM (catmull-rom, R = 64, b = 8). Combinational.
//
// Ports:
//   texels [511:0]  the 16 taps; tap (i, j) = texel (i0 - 1 + i, j0 - 1 + j), i, j = 0..3, in
//                   word 4 j + i: bits [32 (4j+i) +: 32]; channel k in bits [8k+7:8k] of a word
//   fu, fv [7:0]    subtexel fractions (Q.8)
//   c      [31:0]   filtered colour
//
// tfu_cubic_weights (2 ROM reads, 15 tile-weight multipliers, complement tap) -> per channel
// tfu_cubic_mac (16 signed multipliers 8 x W2_BITS, adder tree of ACC_BITS) -> tfu_cubic_norm. W2_BITS (9) and
// ACC_BITS (18) come from gen/tfu_cubic_pkg.sv: tfu_svgen computes the exact ranges of the weights
// and of sum c w over every ROM address pair, tighter than the generic 8 + 9 + 4 bits of
// docs/sampler.md, and still exact for every input.
module tfu_cubic_filter (
  input  logic [511:0] texels,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic [31:0]  c
);
  localparam int W2_BITS = tfu_cubic_pkg::W2_BITS;
  localparam int ACC_BITS = tfu_cubic_pkg::ACC_BITS;
  logic [16*W2_BITS-1:0] w;
  tfu_cubic_weights u_w (.fu(fu), .fv(fv), .w(w));

  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic [127:0] cc;
    logic [ACC_BITS-1:0] acc;
    for (genvar k = 0; k < 16; k++) begin : g_tap
      assign cc[8*k +: 8] = texels[32*k + 8*ch +: 8];
    end
    tfu_cubic_mac #(.W2_BITS(W2_BITS), .ACC_BITS(ACC_BITS)) u_mac (.c(cc), .w(w), .acc(acc));
    tfu_cubic_norm #(.A(ACC_BITS)) u_n (.acc(acc), .c(c[8*ch +: 8]));
  end
endmodule
