// expect: E2027 @6:10
connector Signal
  Real s;
end Signal;
block B
  Signal u;
  output Real y = 1;
end B;
