// Edge-preserving interpolator of Lee & Jen 2003 (Sec. 2.2, 2.3, 3, 6), fully pipelined, RGBA8;
// bit-exact with lee_jen::edge_preserving_interpolate (cmodel/edge_filter.cpp) for the nine kernel
// shapes (cross, T0..T3, L0..L3). VS16X2 is not in the SV (docs/sv-edge.md).
//
// Ports:
//   clk, rst_n        rising-edge clock; synchronous active-low reset (clears the valid bits only)
//   in_valid          a request on texels, shape, fu, fv
//   texels [383:0]    C1..C12 (RGBA8, R in the low byte), Cn at bits [32(n-1) +: 32]; texels missing
//                     from `shape` are never used
//   shape  [11:0]     available texels, bit n-1 = Cn (one of the nine kernel shapes)
//   fu, fv [7:0]      fractions of the sample point in the centre square C4 C5 C8 C9, Q.8
//   out_valid, c [31:0]  the interpolated texel, registered
// One request per clock, no backpressure.
//
// Pipeline, latency 3 clocks (Lee & Jen Sec. 6: "3-clock latency"): a request on the inputs at
// rising edge n is on out_valid / c after edge n + 2. Inputs feed stage 1's logic directly (the
// texels arrive from the texel cache's registers).
//   S1  12 x RGB->Y (carry-save adder trees), keys Y * 16 + n, the 40-cell median network with its
//       T/L input select                        -> R1: texels, shape, fu, fv, low[1..12] (4 bits each)
//   S2  low-pass texel select (Cn_low), 22 x (|dR| + |dG| + |dB|, weight ROM, w * dP), min tree
//                                               -> R2: Cn_low (12 x RGBA), C4 C5 C8 C9, direction, fu, fv
//   S3  endpoint select of the direction, Eq. 3 lerp, Eq. 5 high-frequency bilinear, Eq. 6 clamp
//                                               -> R3: out_valid, c
module tfu_edge_interp_top (
  input  logic         clk,
  input  logic         rst_n,
  input  logic         in_valid,
  input  logic [383:0] texels,
  input  logic [11:0]  shape,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic         out_valid,
  output logic [31:0]  c
);
  // ---------------- S1: RGB->Y, keys, medians ----------------
  logic [191:0] key;
  for (genvar n = 0; n < 12; n++) begin : g_key
    logic [11:0] y;
    tfu_edge_rgb_to_y u_y (.r(texels[32*n +: 8]), .g(texels[32*n + 8 +: 8]), .b(texels[32*n + 16 +: 8]), .y(y));
    assign key[16*n +: 16] = {y, 4'(n + 1)};
  end
  logic [47:0] low;
  tfu_median_network u_median (.key(key), .shape(shape), .low(low));

  logic         v1;
  logic [383:0] texels_1;
  logic [11:0]  shape_1;
  logic [7:0]   fu_1, fv_1;
  logic [47:0]  low_1;
  always_ff @(posedge clk) begin
    if (!rst_n) v1 <= 1'b0;
    else v1 <= in_valid;
    texels_1 <= texels;
    shape_1  <= shape;
    fu_1     <= fu;
    fv_1     <= fv;
    low_1    <= low;
  end

  // ---------------- S2: low-pass texels, direction select ----------------
  logic [383:0] lowtex;
  tfu_edge_lowpass_select u_lowsel (.texels(texels_1), .low(low_1), .lowtex(lowtex));
  logic [287:0] lowrgb;
  for (genvar n = 0; n < 12; n++) begin : g_rgb
    assign lowrgb[24*n +: 24] = lowtex[32*n +: 24];
  end
  logic [4:0] dir;
  /* verilator lint_off UNUSEDSIGNAL */  // the cost is a test/debug output of the block
  logic [17:0] cost;
  /* verilator lint_on UNUSEDSIGNAL */
  tfu_edge_dir_select u_dirsel (.lowrgb(lowrgb), .shape(shape_1), .fu4(fu_1[7:4]), .fv4(fv_1[7:4]), .dir(dir), .cost(cost));

  logic [127:0] centre_1;  // the centre square (tfu_edge_pkg::CENTRE) in the order of Eq. 5's weights
  for (genvar k = 0; k < 4; k++) begin : g_centre
    assign centre_1[32*k +: 32] = texels_1[32*(32'(tfu_edge_pkg::CENTRE[4*k +: 4]) - 1) +: 32];
  end

  logic         v2;
  logic [383:0] lowtex_2;
  logic [127:0] centre_2;
  logic [4:0]   dir_2;
  logic [7:0]   fu_2, fv_2;
  always_ff @(posedge clk) begin
    if (!rst_n) v2 <= 1'b0;
    else v2 <= v1;
    lowtex_2 <= lowtex;
    centre_2 <= centre_1;
    dir_2    <= dir;
    fu_2     <= fu_1;
    fv_2     <= fv_1;
  end

  // ---------------- S3: Eq. 3, 5, 6 ----------------
  logic [31:0] merged;
  tfu_edge_merge u_merge (.lowtex(lowtex_2), .centre(centre_2), .dir(dir_2), .fu(fu_2), .fv(fv_2), .c(merged));
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else out_valid <= v2;
    c <= merged;
  end
endmodule
