// expect: E2029 @10:6
impure function g
  input Real u;
  output Boolean b = u > 0;
end g;
pure function f
  input Real u;
  output Real y;
algorithm
  if g(u) then
    y := u;
  else
    y := -u;
  end if;
end f;
