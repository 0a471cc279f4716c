// expect: E2029 @10:12
impure function g
  input Real u;
  output Real y = u;
end g;
pure function f
  input Real u;
  output Real y;
protected
  Real t = g(u);
algorithm
  y := t;
end f;
