// As one_driver.v, but the NAND2X1 drives another net: _0_ has a load (the flip-flop's D) and no driver.
// The structural check must fail naming _0_.
module tfu_check_undriven(clk, a, \b[0] , y);
  input clk;
  wire clk;
  input a;
  wire a;
  input \b[0] ;
  wire \b[0] ;
  output y;
  wire y;
  wire _0_;
  wire _9_;
  wire \u_x.q[1] ;
  NAND2X1 _1_ (
    .A(a),
    .B(\b[0] ),
    .Y(_9_)
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
