function f
  input Real x;
  output Real y;
equation
  y = 2 * x;
end f;
