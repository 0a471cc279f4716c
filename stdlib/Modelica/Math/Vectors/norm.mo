within Modelica.Math.Vectors;
function norm "Return the p-norm of a vector"
  input Real v[:] "Real vector";
  input Real p(min=1) = 2
    "Type of p-norm (often used: 1, 2, or Modelica.Constants.inf)";
  output Real result=0.0 "p-norm of vector v";
protected
  Real eps = 10*Modelica.Constants.eps;
algorithm
  if size(v, 1) > 0 then
    if p >= 2 - eps and p <= 2 + eps then
      result := sqrt(v*v);
    elseif p >= Modelica.Constants.inf then
      result := max(abs(v));
    elseif p >= 1 - eps and p <= 1 + eps then
      result := sum(abs(v));
    elseif p >= 1 then
      result := (sum(abs(v[i])^p for i in 1:size(v, 1)))^(1/p);
    else
      assert(false, "Optional argument \"p\" (= " + String(p) + ") of function \"norm\" >= 1 required");
    end if;
  end if;
end norm;
