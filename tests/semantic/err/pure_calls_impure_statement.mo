// expect: E2029 @9:3
impure function log
  input Real u;
end log;
pure function f
  input Real u;
  output Real y;
algorithm
  log(u);
  y := u;
end f;
