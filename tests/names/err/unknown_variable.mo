model A
  Real x(start = 1);
  Real velocity;
equation
  der(x) = velocty;
  velocity = -x;
end A;
