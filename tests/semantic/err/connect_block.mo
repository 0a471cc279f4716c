// expect: E2030 @10:11
block B
  output Real y = 1;
end B;
connector S = input Real;
model M
  B b;
  S s;
equation
  connect(b, s);
end M;
