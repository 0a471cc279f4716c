// An impure function calls an impure function.
impure function g
  input Real u;
  output Real y = u;
end g;
impure function f
  input Real u;
  output Real y;
algorithm
  y := g(u);
end f;
