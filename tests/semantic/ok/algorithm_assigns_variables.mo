// An algorithm assigns variables, reading parameters and constants.
model M
  parameter Real p = 1;
  constant Real c = 2;
  Real x;
  Real y;
algorithm
  x := p + c;
  y := 2*x;
end M;
