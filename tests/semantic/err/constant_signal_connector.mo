// expect: E2028 @5:22
// A constant of a signal connector type is still a connector component.
connector RealInput = input Real;
block B
  constant RealInput u = 1;
  output Real y = u;
end B;
