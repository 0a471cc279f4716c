// expect: E2022 @11:16
model Inner
protected
  Real h = 1;
end Inner;
model Outer
  Inner i;
end Outer;
model M
  Outer o;
  Real y = o.i.h;
end M;
