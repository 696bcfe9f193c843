// A hand-made netlist of osu035 cells in the form scripts/gate_count writes (write_verilog -noexpr):
// every net with loads has one driver. The structural check must accept it.
module tfu_check_ok(clk, a, \b[0] , y);
  input clk;
  wire clk;
  input a;
  wire a;
  input \b[0] ;
  wire \b[0] ;
  output y;
  wire y;
  wire _0_;
  wire \u_x.q[1] ;
  NAND2X1 _1_ (
    .A(a),
    .B(\b[0] ),
    .Y(_0_)
  );
  DFFPOSX1 \u_x.q[1]$DFFPOSX1  (
    .CLK(clk),
    .D(_0_),
    .Q(\u_x.q[1] )
  );
  INVX1 _2_ (
    .A(\u_x.q[1] ),
    .Y(y)
  );
endmodule
