// Cubic output normalisation (Hadwiger 2004 Sec. 3.5: weights at scale M = 2^b - 1; cmodel/
// sampler.cpp Sampler::sample_level_filter, CUBIC, M = 255): c = clamp(floor((2 acc + M) / (2 M)),
// 0, 255), i.e. acc / M rounded half up, then clamped to the unorm8 range. Combinational.
//
// Parameter A: accumulator width (default tfu_cubic_pkg::ACC_BITS, generated; at least 17).
// Ports:
//   acc [A-1:0] signed  sum c w of one channel, weights at scale M = 255
//   c   [7:0]           normalised, clamped channel
//
// No divider: floor((2 acc + 255) / 510) = floor((acc + 127) / 255) for acc >= 0, and for
// m = acc + 127 <= 65279 the constant division is (m + 1 + (m >> 8)) >> 8 (exact for m < 65535).
// acc < 0 gives c < 1/2 -> 0; acc >= 65153 gives c >= 255.5 -> 255 (both ends exact; the
// equivalence test checks every acc of the accumulator range).
module tfu_cubic_norm #(
  parameter int A = tfu_cubic_pkg::ACC_BITS
) (
  input  logic signed [A-1:0] acc,
  output logic [7:0]          c
);
  logic [16:0] m;      // acc + 127 in 0..65279 when used
  logic [16:0] t;      // m + 1 + (m >> 8)
  assign m = 17'(acc[15:0]) + 17'd127;
  assign t = m + 17'd1 + {8'b0, m[16:8]};
  always_comb begin
    if (acc < 0) c = 8'd0;
    else if (acc >= A'(65153)) c = 8'd255;
    else c = 8'(t >> 8);
  end
endmodule
