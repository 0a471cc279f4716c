// expect: E2032 @8:13
model M
  parameter Boolean on = true;
  Real x = sin(time);
  Real y;
equation
  if on then
    y = pre(x);
  else
    y = 0;
  end if;
end M;
