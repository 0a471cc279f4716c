// expect: E2004 @3:23
model M
  parameter Boolean b(nominal = true) = true;
end M;
