model A
  Real x = Modelica.Constants.pie;
end A;
