// expect: E2022 @10:10
model A
protected
  Boolean b = time > 1;
end A;
model M
  A a;
  discrete Real y(start = 0);
equation
  when a.b then
    y = 1;
  end when;
end M;
