// An output that follows a top-level input algebraically, differentiated: index
// reduction differentiates y = 2*u and needs der(u), which an input does not have.
model DifferentiatedInput
  input Real u;
  Real y;
  Real z;
equation
  y = 2 * u;
  z = der(y);
end DifferentiatedInput;
