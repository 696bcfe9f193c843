// Endpoints of the chosen direction (Lee & Jen 2003 Eq. 3): Cp_low, Cq_low and the blend parameter
// t = fu or fv of direction `dir`; the first part of tfu_edge_merge. Endpoints and blend axis of each
// direction: package tfu_edge_pkg (gen/tfu_edge_pkg.sv, from lee_jen::directions()).
//
// Ports:
//   lowtex [383:0]  Cn_low (RGBA) at bits [32(n-1) +: 32]
//   dir    [4:0]    chosen direction, 0..21 (tfu_edge_dir_select)
//   fu, fv [7:0]    fractions of the sample point, Q.8
//   cp, cq [31:0]   Cp_low, Cq_low of direction dir
//   t      [7:0]    fv if the direction blends along y, else fu
// Combinational: two 32-bit 22:1 AND-OR muxes on the decoded direction.
module tfu_edge_endpoints (
  input  logic [383:0] lowtex,
  input  logic [4:0]   dir,
  input  logic [7:0]   fu,
  input  logic [7:0]   fv,
  output logic [31:0]  cp,
  output logic [31:0]  cq,
  output logic [7:0]   t
);
  localparam int NDIR = tfu_edge_pkg::NDIR;
  localparam logic [4*NDIR-1:0] DIR_P = tfu_edge_pkg::DIR_P;
  localparam logic [4*NDIR-1:0] DIR_Q = tfu_edge_pkg::DIR_Q;
  localparam logic [NDIR-1:0] DIR_AXIS_Y = tfu_edge_pkg::DIR_AXIS_Y;
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
endmodule
