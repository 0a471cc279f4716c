function f
  input Real x;
  output Real a;
  output Real b;
algorithm
  a := x;
  b := x;
end f;

model A
  Real p;
  Real q;
algorithm
  (p, 2) := f(1);
  q := p;
end A;
