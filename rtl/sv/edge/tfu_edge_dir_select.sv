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
// Structure: 22 x (three 8-bit |a - b| and a 10-bit sum: tfu_edge_dir_dp; a weight ROM; an 8 x 10
// multiplier: tfu_edge_dir_leaves), then a five-level binary min tree over 32 leaves (leaves 22..31
// unusable; tfu_edge_min_level); at each node the lower-index side wins unless the other side is
// usable and strictly cheaper, which gives "ties -> lowest index" for the whole tree. The pipelined
// top (tfu_edge_interp_top) uses the same parts with registers between them. Combinational.
module tfu_edge_dir_select (
  input  logic [287:0] lowrgb,
  input  logic [11:0]  shape,
  input  logic [3:0]   fu4,
  input  logic [3:0]   fv4,
  output logic [4:0]   dir,
  output logic [17:0]  cost
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam int E = 24;  // node of the min tree: {usable, cost[17:0], index[4:0]}
  logic [8*NDIR-1:0]  w;
  logic [10*NDIR-1:0] dp;
  logic [32*E-1:0]    leaf;
  tfu_edge_dir_roms u_roms (.fu(fu4), .fv(fv4), .w(w));
  tfu_edge_dir_dp u_dp (.lowrgb(lowrgb), .dp(dp));
  tfu_edge_dir_leaves u_leaves (.dp(dp), .w(w), .shape(shape), .leaf(leaf));

  // Min tree: 32 -> 16 -> 8 -> 4 -> 2 -> 1.
  logic [16*E-1:0] l1;
  logic [8*E-1:0]  l2;
  logic [4*E-1:0]  l3;
  logic [2*E-1:0]  l4;
  logic [E-1:0]    root;
  tfu_edge_min_level #(.N(32)) u_l1 (.in(leaf), .out(l1));
  tfu_edge_min_level #(.N(16)) u_l2 (.in(l1), .out(l2));
  tfu_edge_min_level #(.N(8)) u_l3 (.in(l2), .out(l3));
  tfu_edge_min_level #(.N(4)) u_l4 (.in(l3), .out(l4));
  tfu_edge_min_level #(.N(2)) u_l5 (.in(l4), .out(root));

  assign dir  = root[E-1] ? root[4:0] : 5'd0;
  assign cost = root[E-1] ? root[E-2:5] : 18'd0;
endmodule
