// x1 = sin(time), x(k+1) = der(x(k)): structural index 5 (x1 is differentiated four times).
model DerivativeChain
  Real x1, x2, x3, x4, x5;
equation
  x1 = sin(time);
  x2 = der(x1);
  x3 = der(x2);
  x4 = der(x3);
  x5 = der(x4);
end DerivativeChain;
