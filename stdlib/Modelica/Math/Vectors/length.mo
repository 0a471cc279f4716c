within Modelica.Math.Vectors;
function length
  "Return length of a vector (better as norm(), if further symbolic processing is performed)"
  input Real v[:] "Real vector";
  output Real result "Length of vector v";
algorithm
  result := sqrt(v*v);
  annotation (Inline=true);
end length;
