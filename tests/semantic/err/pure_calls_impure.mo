// expect: E2029 @10:8
impure function g
  input Real u;
  output Real y = u;
end g;
pure function f
  input Real u;
  output Real y;
algorithm
  y := g(u);
end f;
