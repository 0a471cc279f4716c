// Constants bound to constants and literals; parameters bound to constants.
model M
  constant Real a = 1;
  constant Real b = 2*a + 1;
  parameter Real p = b;
  Real x = p;
end M;
