// expect: E1221 @4:1
connector C
  Real v;
equation
  v = 1;
end C;
