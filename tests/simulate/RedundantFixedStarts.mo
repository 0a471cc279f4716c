model RedundantFixedStarts "Fixed starts on both ends of a rigid link: redundant, and consistent when x2 = x1 + L holds for them"
  parameter Real L = 1;
  parameter Real x2_start = 1;
  Real x1(start = 0, fixed = true);
  Real x2(start = x2_start, fixed = true);
  Real v1(start = 0, fixed = true);
  Real v2;
equation
  x2 = x1 + L;
  der(x1) = v1;
  der(x2) = v2;
  der(v1) = -x1 - 0.5;
end RedundantFixedStarts;
