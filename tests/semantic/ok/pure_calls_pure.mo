// A pure function calls pure and unprefixed functions.
function h
  input Real u;
  output Real y = 3*u;
end h;
pure function g
  input Real u;
  output Real y = 2*u;
end g;
pure function f
  input Real u;
  output Real y;
algorithm
  y := g(h(u));
end f;
