// expect: E2019 @4:21
model M
  parameter Boolean b = true;
  constant Real c = if b then 1 else 2;
  Real x = c;
end M;
