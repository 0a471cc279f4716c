within Modelica.Math.Vectors;
function normalize
  "Return normalized vector such that length = 1 and prevent zero-division for zero vector"
  input Real v[:] "Real vector";
  input Real eps(min=0.0) = 100*Modelica.Constants.eps
    "if |v| < eps then result = v/eps";
  output Real result[size(v, 1)] "Input vector v normalized to length=1";
algorithm
  /* This function has the inline annotation. If the function is inlined:
     - "smooth(..)" defines how often the expression can be differentiated
       (if symbolic processing is performed).
  */
  result := smooth(0, if length(v) >= eps then v/length(v) else v/eps);
  annotation (Inline=true);
end normalize;
