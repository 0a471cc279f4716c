model A
  import SI = Modelica.SIunits;
  SI.Lenght x;
equation
  x = 1;
end A;
