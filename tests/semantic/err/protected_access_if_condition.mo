// expect: E2022 @10:8
model A
protected
  parameter Boolean on = true;
end A;
model M
  A a;
  Real y;
equation
  if a.on then
    y = 1;
  else
    y = 2;
  end if;
end M;
