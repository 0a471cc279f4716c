// A function with no purity prefix may call an impure one (deprecated, spec 12.3).
impure function g
  input Real u;
  output Real y = u;
end g;
function f
  input Real u;
  output Real y;
algorithm
  y := g(u);
end f;
