// Pipelined bilinear filter, 8-bit RGBA (the gate-count baseline of docs/gates.md): the bilinear
// lerp unit (GL 4.6 Sec. 8.14.2; tfu::dp::bilinear_lerp) between registers. Bit-exact with
// dp::bilinear_lerp (c) and dp::bilinear_lerp_q8 (q, the Q.8 result the trilinear blend unit
// tfu_level_blend takes); one result per clock, no backpressure (en = 0 freezes every register).
//
// Ports:
//   clk, rst_n        rising-edge clock, synchronous active-low reset (clears the valid bits only)
//   en                clock enable of all stages (stall)
//   in_valid          a request on c00..c11, fu, fv
//   c00, c10, c01, c11 [31:0], fu, fv [7:0]   as tfu_bilinear_lerp
//   out_valid, q [63:0]                       Q.8 result, registered: channel k in [16k+15:16k],
//                                             (sum c w) >> 8 (tfu_lerp_v_sum)
//   c [31:0]                                  q rounded per channel, (q + 128) >> 8 = (sum c w + 2^15)
//                                             >> 16 (tfu_level_round after the output register)
//
// Parameter:
//   CUT_V  1: a register inside the vertical lerp, between d = h1 - h0 (tfu_lerp_v_diff) and the
//          product and rounding sum (tfu_lerp_v_sum): latency 4, the depth that meets 101.2 MHz in
//          OSU 0.35 um (docs/silicon.md; wrapper tfu_bilinear_top_l4). 0 (default): latency 3.
//
// Pipeline (latency LATENCY = 3 + CUT_V clocks: a request sampled at rising edge n, with en = 1 on
// LATENCY consecutive edges, is on out_valid / c after edge n + LATENCY - 1):
//   S1  input registers (texels, fractions)
//   S2  horizontal lerps h0, h1 per channel (tfu_lerp_h, exact 16 bits) and fv
//   S3  vertical lerp to 8 fraction bits (tfu_lerp_v_diff, tfu_lerp_v_sum) -> output register q;
//       with CUT_V: S3 d = h1 - h0 -> register (h0, d, fv), S4 product and sum -> output register q;
//       c = round(q) after the register
module tfu_bilinear_top #(
  parameter bit CUT_V = 1'b0
) (
  input  logic        clk,
  input  logic        rst_n,
  input  logic        en,
  input  logic        in_valid,
  input  logic [31:0] c00,
  input  logic [31:0] c10,
  input  logic [31:0] c01,
  input  logic [31:0] c11,
  input  logic [7:0]  fu,
  input  logic [7:0]  fv,
  output logic        out_valid,
  output logic [63:0] q,
  output logic [31:0] c
);
  // S1
  logic        v1;
  logic [31:0] c00_1, c10_1, c01_1, c11_1;
  logic [7:0]  fu_1, fv_1;
  always_ff @(posedge clk) begin
    if (!rst_n) v1 <= 1'b0;
    else if (en) v1 <= in_valid;
    if (en) begin
      c00_1 <= c00;
      c10_1 <= c10;
      c01_1 <= c01;
      c11_1 <= c11;
      fu_1  <= fu;
      fv_1  <= fv;
    end
  end

  // S2
  logic        v2;
  logic [7:0]  fv_2;
  logic [15:0] h0_2 [4];
  logic [15:0] h1_2 [4];
  logic [15:0] h0 [4];
  logic [15:0] h1 [4];
  for (genvar ch = 0; ch < 4; ch++) begin : g_h
    tfu_lerp_h u_h0 (.a(c00_1[8*ch +: 8]), .b(c10_1[8*ch +: 8]), .f(fu_1), .h(h0[ch]));
    tfu_lerp_h u_h1 (.a(c01_1[8*ch +: 8]), .b(c11_1[8*ch +: 8]), .f(fu_1), .h(h1[ch]));
  end
  always_ff @(posedge clk) begin
    if (!rst_n) v2 <= 1'b0;
    else if (en) v2 <= v1;
    if (en) begin
      fv_2 <= fv_1;
      for (int ch = 0; ch < 4; ch++) begin
        h0_2[ch] <= h0[ch];
        h1_2[ch] <= h1[ch];
      end
    end
  end

  // S3 (and S4 with CUT_V)
  logic [63:0] qv;
  logic        v3;
  for (genvar ch = 0; ch < 4; ch++) begin : g_v
    logic [16:0] d;
    tfu_lerp_v_diff u_d (.a(h0_2[ch]), .b(h1_2[ch]), .d(d));
    if (CUT_V) begin : g_cut
      logic [15:0] a_3;
      logic [16:0] d_3;
      logic [7:0]  f_3;
      always_ff @(posedge clk) begin
        if (en) begin
          a_3 <= h0_2[ch];
          d_3 <= d;
          f_3 <= fv_2;
        end
      end
      tfu_lerp_v_sum u_v (.a(a_3), .d(d_3), .f(f_3), .q(qv[16*ch +: 16]));
    end else begin : g_comb
      tfu_lerp_v_sum u_v (.a(h0_2[ch]), .d(d), .f(fv_2), .q(qv[16*ch +: 16]));
    end
  end
  if (CUT_V) begin : g_v3
    always_ff @(posedge clk) begin
      if (!rst_n) v3 <= 1'b0;
      else if (en) v3 <= v2;
    end
  end else begin : g_v3_wire
    assign v3 = v2;
  end
  always_ff @(posedge clk) begin
    if (!rst_n) out_valid <= 1'b0;
    else if (en) out_valid <= v3;
    if (en) q <= qv;
  end
  for (genvar ch = 0; ch < 4; ch++) begin : g_round
    tfu_level_round u_r (.q(q[16*ch +: 16]), .c(c[8*ch +: 8]));
  end
endmodule
