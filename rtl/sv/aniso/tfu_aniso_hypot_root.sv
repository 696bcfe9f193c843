// Floor square root of the hypot unit's radicand (tfu_aniso_ellipse_major): h = floor(sqrt(rad)),
// 17 bits of a 34-bit radicand, restoring, digit by digit (two radicand bits and one root bit per
// stage, a 20-bit compare-subtract each); bit-exact with tfu::axis_length_q16's root as used by
// tfu::aniso_hypot (cmodel/aniso.hpp). Combinational.
//
// Ports:
//   rad  [33:0]  M'^2 + m'^2 < 2^33 (tfu_aniso_hypot_square)
//   h    [16:0]  floor(sqrt(rad)) < 2^16.5
module tfu_aniso_hypot_root (
  input  logic [33:0] rad,
  output logic [16:0] h
);
  always_comb begin
    logic [19:0] rem;
    logic [18:0] trial;
    rem = '0;
    h = '0;
    for (int i = 16; i >= 0; i--) begin
      rem = {rem[17:0], rad[2 * i + 1], rad[2 * i]};
      trial = {h, 2'b01};  // 4 root + 1
      if (rem >= 20'(trial)) begin
        rem = rem - 20'(trial);
        h = {h[15:0], 1'b1};
      end else begin
        h = {h[15:0], 1'b0};
      end
    end
  end
endmodule
