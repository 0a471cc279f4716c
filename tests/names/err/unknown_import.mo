model A
  import SI = Modelica.SIunit;
  Real x;
equation
  x = 1;
end A;
