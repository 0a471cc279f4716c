// expect: E2028 @3:15
block B
  stream Real h;
  output Real y = 1;
end B;
