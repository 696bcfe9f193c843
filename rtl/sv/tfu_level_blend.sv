// Trilinear blend unit (GL 4.6 Sec. 8.14.3, *_MIPMAP_LINEAR; bit-exact with tfu::dp::level_blend of
// cmodel/datapath.hpp for 8-bit channels). Combinational.
//
// Ports:
//   c0 [31:0]  filtered colour of level floor(lambda)      channel k in bits [8k+7:8k]
//   c1 [31:0]  filtered colour of level floor(lambda) + 1
//   f   [7:0]  weight of level 1: lambda & 255 (Q.8)
//   c  [31:0]  per channel (c0 (256 - f) + c1 f + 128) >> 8, rounding half up
module tfu_level_blend (
  input  logic [31:0] c0,
  input  logic [31:0] c1,
  input  logic [7:0]  f,
  output logic [31:0] c
);
  for (genvar ch = 0; ch < 4; ch++) begin : g_ch
    logic [15:0] h;
    tfu_lerp_h u_l (.a(c0[8*ch +: 8]), .b(c1[8*ch +: 8]), .f(f), .h(h));
    assign c[8*ch +: 8] = 8'((h + 16'd128) >> 8);  // h <= 65280: no carry out of 16 bits
  end
endmodule
