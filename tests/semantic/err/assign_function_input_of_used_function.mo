// expect: E2026 @6:3
function f
  input Real u;
  output Real y;
algorithm
  u := 2*u;
  y := u;
end f;
model M "flattening M reports the error of f, its file's other class"
  Real x = f(time);
end M;
