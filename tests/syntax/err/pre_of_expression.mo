model A
  Real x;
  Boolean b;
equation
  der(x) = 1;
  b = pre(x > 1);
end A;
