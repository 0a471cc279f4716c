// An array written on the type (`Real[2] x`).
model M
  Real[2] x(each start = 1, each fixed = true);
equation
  der(x) = -x;
end M;
