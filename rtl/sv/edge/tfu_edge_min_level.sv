// One level of the direction select's min tree (Lee & Jen 2003 Eq. 2: the direction of least
// weighted difference): N nodes {usable, cost[17:0], index[4:0]} -> N/2. Node k of the output is
// the pick of input nodes 2k (lower indices) and 2k+1: the lower-index side wins unless the other
// side is usable and strictly cheaper, which over the whole tree gives "ties -> lowest index"
// (lee_jen::select_direction).
//
// Ports:
//   in  [24N-1:0]    node k at bits [24k +: 24]
//   out [12N-1:0]    node k at bits [24k +: 24]
// Combinational: N/2 18-bit comparators and 24-bit 2:1 muxes.
module tfu_edge_min_level #(
  parameter int N = 32
) (
  input  logic [24*N-1:0]     in,
  output logic [24*(N/2)-1:0] out
);
  localparam int E = 24;
  function automatic logic [E-1:0] pick(input logic [E-1:0] lo_side, input logic [E-1:0] hi_side);
    pick = (hi_side[E-1] && (!lo_side[E-1] || hi_side[E-2:5] < lo_side[E-2:5])) ? hi_side : lo_side;
  endfunction
  for (genvar k = 0; k < N / 2; k++) begin : g_node
    assign out[E*k +: E] = pick(in[E*(2*k) +: E], in[E*(2*k+1) +: E]);
  end
endmodule
