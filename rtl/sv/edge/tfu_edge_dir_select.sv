// Direction select of the edge-preserving filter (Lee & Jen 2003 Eq. 1-2, Sec. 3), RGBA8; bit-exact
// with lee_jen::select_direction (cmodel/edge_filter.cpp):
//   dP_i   = |dR| + |dG| + |dB| between the low-pass endpoints Cp_low, Cq_low of direction i
//            (10 bits, 0..765)
//   w_i    = direction ROM i at {fv4, fu4} (gen/tfu_edge_dir_rom_NN.sv; 8 bits, 4.4, 255 = never)
//   cost_i = w_i * dP_i (18 bits, at most 254 * 765 = 194310)
//   usable = both endpoints available in `shape` and w_i != 255
//   dir    = argmin of cost_i over the usable directions, ties to the lowest index; if no direction
//            is usable (impossible for the nine kernel shapes), dir = 0 and cost = 0, as the model.
// Direction order, endpoints: package tfu_edge_pkg (gen/tfu_edge_pkg.sv, from lee_jen::directions()).
//
// Ports:
//   lowrgb [287:0]  R, G, B of Cn_low at bits [24(n-1) +: 24] (R in the low byte)
//   shape  [11:0]   available texels, bit n-1 = Cn
//   fu4, fv4 [3:0]  top nibbles of the 8-bit fractions (the ROM address)
//   dir    [4:0]    chosen direction index, 0..21
//   cost   [17:0]   its cost w * dP
//
// Structure: 22 x (three 8-bit |a - b|, a 10-bit sum, a weight ROM, an 8 x 10 multiplier), then a
// five-level binary min tree over 32 leaves (leaves 22..31 unusable); at each node the lower-index
// side wins unless the other side is usable and strictly cheaper, which gives "ties -> lowest
// index" for the whole tree. Combinational.
module tfu_edge_dir_select (
  input  logic [287:0] lowrgb,
  input  logic [11:0]  shape,
  input  logic [3:0]   fu4,
  input  logic [3:0]   fv4,
  output logic [4:0]   dir,
  output logic [17:0]  cost
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam logic [4*NDIR-1:0] DIR_P = tfu_edge_pkg::DIR_P;
  localparam logic [4*NDIR-1:0] DIR_Q = tfu_edge_pkg::DIR_Q;
  logic [8*NDIR-1:0] w;
  tfu_edge_dir_roms u_roms (.fu(fu4), .fv(fv4), .w(w));

  function automatic logic [9:0] absdiff(input logic [7:0] a, input logic [7:0] b);
    absdiff = a > b ? {2'b00, a - b} : {2'b00, b - a};
  endfunction

  // Leaf / node of the min tree: {usable, cost[17:0], index[4:0]}.
  localparam int E = 24;
  function automatic logic [E-1:0] pick(input logic [E-1:0] lo_side, input logic [E-1:0] hi_side);
    pick = (hi_side[E-1] && (!lo_side[E-1] || hi_side[E-2:5] < lo_side[E-2:5])) ? hi_side : lo_side;
  endfunction

  logic [32*E-1:0] leaf;
  for (genvar i = 0; i < 32; i++) begin : g_dir
    if (i < NDIR) begin : g_used
      localparam int P = 32'(DIR_P[4*i +: 4]) - 1;  // bit index of Cp in shape
      localparam int Q = 32'(DIR_Q[4*i +: 4]) - 1;
      logic [9:0]  dp;
      logic [17:0] c;
      logic [7:0]  wi;
      assign wi = w[8*i +: 8];
      assign dp = absdiff(lowrgb[24*P +: 8], lowrgb[24*Q +: 8]) + absdiff(lowrgb[24*P + 8 +: 8], lowrgb[24*Q + 8 +: 8]) +
                  absdiff(lowrgb[24*P + 16 +: 8], lowrgb[24*Q + 16 +: 8]);
      assign c = {10'b0, wi} * {8'b0, dp};
      assign leaf[E*i +: E] = {shape[P] & shape[Q] & (wi != 8'hFF), c, 5'(i)};
    end else begin : g_pad
      assign leaf[E*i +: E] = '0;
    end
  end

  // Min tree: 32 -> 16 -> 8 -> 4 -> 2 -> 1.
  logic [16*E-1:0] l1;
  logic [8*E-1:0]  l2;
  logic [4*E-1:0]  l3;
  logic [2*E-1:0]  l4;
  logic [E-1:0]    root;
  for (genvar k = 0; k < 16; k++) begin : g_l1
    assign l1[E*k +: E] = pick(leaf[E*(2*k) +: E], leaf[E*(2*k+1) +: E]);
  end
  for (genvar k = 0; k < 8; k++) begin : g_l2
    assign l2[E*k +: E] = pick(l1[E*(2*k) +: E], l1[E*(2*k+1) +: E]);
  end
  for (genvar k = 0; k < 4; k++) begin : g_l3
    assign l3[E*k +: E] = pick(l2[E*(2*k) +: E], l2[E*(2*k+1) +: E]);
  end
  for (genvar k = 0; k < 2; k++) begin : g_l4
    assign l4[E*k +: E] = pick(l3[E*(2*k) +: E], l3[E*(2*k+1) +: E]);
  end
  assign root = pick(l4[0 +: E], l4[E +: E]);

  assign dir  = root[E-1] ? root[4:0] : 5'd0;
  assign cost = root[E-1] ? root[E-2:5] : 18'd0;
endmodule
