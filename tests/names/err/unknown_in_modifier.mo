model A
  parameter Real x0 = 1;
  Real x(start = xo);
equation
  der(x) = -x;
end A;
