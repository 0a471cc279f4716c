// expect: E2027 @6:8
connector Pin
  Real v;
  flow Real i;
protected
  Real w;
end Pin;
