// Cap and rounding of the probe count (both count units, tfu_aniso_count and
// tfu_aniso_count_ellipse): N = min(count, maxAniso), then rounded up to a power of two when
// aniso_rounding is set (the spec's "round N up to the nearest supported sampling rate"); the
// last lines of tfu::aniso_probe_count and tfu::aniso_probe_count_ellipse. Combinational.
//
// Ports:
//   count           [4:0]  1..17 (17: no compare passed)
//   max_aniso       [4:0]  maxAniso, 1..16 (0 acts as 1, 17..31 as 16)
//   aniso_rounding         1: round up to 1, 2, 4, 8, 16
//   probes          [4:0]  N, 1..16
module tfu_aniso_cap_round (
  input  logic [4:0] count,
  input  logic [4:0] max_aniso,
  input  logic       aniso_rounding,
  output logic [4:0] probes
);
  logic [4:0] cap;
  assign cap = (max_aniso == 5'd0) ? 5'd1 : (max_aniso > 5'd16) ? 5'd16 : max_aniso;

  logic [4:0] n;
  assign n = (count < cap) ? count : cap;
  always_comb begin
    if (!aniso_rounding || n <= 5'd2) probes = n;
    else if (n <= 5'd4) probes = 5'd4;
    else if (n <= 5'd8) probes = 5'd8;
    else probes = 5'd16;
  end
endmodule
