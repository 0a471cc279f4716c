function f
  input Real x;
  output Real y;
algorithm
  y := der(x);
end f;
