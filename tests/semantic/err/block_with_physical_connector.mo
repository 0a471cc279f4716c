// expect: E2027 @7:7
connector Pin
  Real v;
  flow Real i;
end Pin;
block B
  Pin p;
equation
  p.v = 0;
end B;
