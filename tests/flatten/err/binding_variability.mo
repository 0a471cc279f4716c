model BindingVariability "Bindings of higher variability than their variable (spec 3.8)"
  constant Real c = time;
  parameter Real p = x;
  parameter Integer n = size(v, 1) "legal: size reads the structure of v";
  Real x = 1;
  Real v[3] = fill(x, 3);
end BindingVariability;
