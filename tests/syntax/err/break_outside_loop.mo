function f
  input Real x;
  output Real y;
algorithm
  y := x;
  break;
end f;
