// Merge of the edge-preserving filter (Lee & Jen 2003 Eq. 3, 5, 6), RGBA8; bit-exact with
// lee_jen::edge_merge (cmodel/edge_filter.cpp). Per channel (alpha included):
//   C_low  = ((256 - t) Cp_low + t Cq_low + 128) >> 8          t = fu or fv of direction `dir` (Eq. 3)
//          = (256 Cp_low + t (Cq_low - Cp_low) + 128) >> 8     (one signed 8 x 9 multiplier)
//   H_n    = C_n - Cn_low, n = 4, 5, 8, 9                      9 bits signed
//   C_high = (sum H_n w_n + 2^15) >> 16 (floor), w_n the bilinear weights (256 - fu | fu)(256 - fv | fv)
//            computed exactly as two lerps: h0 = 256 H4 + fu (H5 - H4), h1 = 256 H8 + fu (H9 - H8),
//            sum = 256 h0 + fv (h1 - h0)   (Eq. 5; no rounding before the last shift)
//   I      = clamp(C_low + C_high, 0, 255)                    (Eq. 6)
// Endpoints and blend axis of each direction: package tfu_edge_pkg (gen/tfu_edge_pkg.sv).
//
// Ports:
//   lowtex [383:0]  Cn_low (RGBA) at bits [32(n-1) +: 32], R in the low byte
//   centre [127:0]  C4, C5, C8, C9 (RGBA) at bits [0 +: 32], [32 +: 32], [64 +: 32], [96 +: 32]
//   dir    [4:0]    chosen direction, 0..21 (tfu_edge_dir_select)
//   fu, fv [7:0]    fractions of the sample point in the centre square, Q.8
//   c      [31:0]   interpolated texel
// Combinational.
module tfu_edge_merge (
  input  logic [383:0] lowtex,
  input  logic [127:0] centre,
  input  logic [4:0]   dir,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic [31:0]  c
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam logic [4*NDIR-1:0] DIR_P = tfu_edge_pkg::DIR_P;
  localparam logic [4*NDIR-1:0] DIR_Q = tfu_edge_pkg::DIR_Q;
  localparam logic [NDIR-1:0] DIR_AXIS_Y = tfu_edge_pkg::DIR_AXIS_Y;
  // Endpoints of the chosen direction (22:1 AND-OR muxes) and its blend parameter t.
  logic [31:0] cp, cq;
  logic [7:0]  t;
  always_comb begin
    cp = '0;
    cq = '0;
    t = fu;
    for (int i = 0; i < NDIR; i++) begin
      if (dir == 5'(i)) begin
        cp = lowtex[32*(32'(DIR_P[4*i +: 4]) - 1) +: 32];
        cq = lowtex[32*(32'(DIR_Q[4*i +: 4]) - 1) +: 32];
        t = DIR_AXIS_Y[i] ? fv : fu;
      end
    end
  end

  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    // Eq. 3
    logic signed [8:0]  dq;     // Cq - Cp, -255..255
    logic signed [17:0] lw;     // 256 Cp + t (Cq - Cp) + 128, 128..65408
    logic [7:0]         clow;
    assign dq = $signed({1'b0, cq[8*ch +: 8]}) - $signed({1'b0, cp[8*ch +: 8]});
    assign lw = $signed({2'b00, cp[8*ch +: 8], 8'd128}) + 18'(dq * $signed({1'b0, t}));
    assign clow = 8'(lw >>> 8);

    // Eq. 5: H_n and the exact bilinear sum.
    logic signed [8:0]  h4, h5, h8, h9;     // -255..255
    logic signed [9:0]  dx0, dx1;           // H5 - H4, H9 - H8
    logic signed [18:0] hx0, hx1;           // 256 H4 + fu (H5 - H4), |.| <= 255 * 256
    logic signed [19:0] dy;                 // hx1 - hx0
    logic signed [27:0] hs;                 // 256 hx0 + fv (hx1 - hx0) + 2^15, |.| <= 255 * 2^16 + 2^15
    logic signed [9:0]  chigh;              // -255..255
    assign h4 = $signed({1'b0, centre[8*ch +: 8]}) - $signed({1'b0, lowtex[32*3 + 8*ch +: 8]});
    assign h5 = $signed({1'b0, centre[32 + 8*ch +: 8]}) - $signed({1'b0, lowtex[32*4 + 8*ch +: 8]});
    assign h8 = $signed({1'b0, centre[64 + 8*ch +: 8]}) - $signed({1'b0, lowtex[32*7 + 8*ch +: 8]});
    assign h9 = $signed({1'b0, centre[96 + 8*ch +: 8]}) - $signed({1'b0, lowtex[32*8 + 8*ch +: 8]});
    assign dx0 = 10'(h5) - 10'(h4);
    assign dx1 = 10'(h9) - 10'(h8);
    assign hx0 = 19'($signed({h4, 8'd0})) + 19'(dx0 * $signed({1'b0, fu}));
    assign hx1 = 19'($signed({h8, 8'd0})) + 19'(dx1 * $signed({1'b0, fu}));
    assign dy = 20'(hx1) - 20'(hx0);
    assign hs = 28'($signed({hx0, 8'd0})) + 28'(dy * $signed({1'b0, fv})) + 28'sd32768;
    assign chigh = 10'(hs >>> 16);

    // Eq. 6
    logic signed [10:0] sum;  // -255..510
    assign sum = $signed({3'b000, clow}) + 11'(chigh);
    assign c[8*ch +: 8] = sum < 0 ? 8'd0 : (sum > 11'sd255 ? 8'd255 : 8'(sum));
  end
endmodule
