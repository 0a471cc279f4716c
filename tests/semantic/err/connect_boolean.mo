// expect: E2030 @7:14
connector BooleanOutput = output Boolean;
model M
  BooleanOutput o;
  Boolean b;
equation
  connect(o, b);
end M;
