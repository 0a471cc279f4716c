// expect: E2030 @12:14
connector RealInput = input Real;
block B
  input Real u;
  RealInput w;
  output Real y = u + w;
end B;
model M
  B b;
  RealInput s;
equation
  connect(s, b.u);
end M;
