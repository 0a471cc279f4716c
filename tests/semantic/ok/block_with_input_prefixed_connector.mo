// A block's connector whose variables get their causality from the component prefix.
connector Data
  Real value;
end Data;
block B
  input Data u;
  output Real y;
equation
  y = u.value;
end B;
