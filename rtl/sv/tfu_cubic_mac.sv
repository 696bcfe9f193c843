// One channel of the cubic filter's multiply-accumulate tree (Hadwiger 2004 Sec. 3.1: sum c w over
// the 4 x 4 taps), bit-exact with dp::cubic_accumulate for 8-bit channels. Combinational.
//
// Ports:
//   c   [127:0]            the channel's 16 texel codes, tap k in bits [8k+7:8k] (unsigned)
//   w   [16*W2_BITS-1:0]   the 16 signed weights of tfu_cubic_weights, tap k in [W2_BITS k +: W2_BITS]
//   acc [ACC_BITS-1:0]     sum c w (signed; ACC_BITS from gen/tfu_cubic_pkg.sv is exact for every input)
module tfu_cubic_mac #(
  parameter int W2_BITS = 9,
  parameter int ACC_BITS = 18
) (
  input  logic [127:0]            c,
  input  logic [16*W2_BITS-1:0]   w,
  output logic [ACC_BITS-1:0]     acc
);
  always_comb begin
    acc = '0;
    for (int k = 0; k < 16; k++)
      acc = acc + ACC_BITS'($signed({1'b0, c[8*k +: 8]}) * $signed(w[W2_BITS*k +: W2_BITS]));
  end
endmodule
