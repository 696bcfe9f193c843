// As one_driver.v, but the inverter drives the flip-flop's Q net too: \u_x.q[1] has two drivers.
// The structural check must fail naming u_x.q[1].
module tfu_check_two_drivers(clk, a, \b[0] , y);
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
  INVX1 _3_ (
    .A(a),
    .Y(\u_x.q[1] )
  );
endmodule
