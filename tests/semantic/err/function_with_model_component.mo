// expect: E2027 @9:5
model A
  Real y = 1;
end A;
function f
  input Real u;
  output Real y = u;
protected
  A a;
end f;
