// expect: E2004 @3:23
model M
  parameter Integer n(nominal = 10) = 1;
end M;
