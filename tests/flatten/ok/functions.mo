function square
  input Real u;
  output Real y;
algorithm
  y := u * u;
end square;

model Functions
  Real x(start = 1, fixed = true);
  Real s = square(x);
  Real n = Modelica.Math.Vectors.norm({3, 4});
equation
  der(x) = -square(x) + Modelica.Constants.pi;
end Functions;
