model ParameterBindingCycle "Parameters whose bindings depend on each other (spec 4.4.4); no compile-time evaluation needs them"
  parameter Real a = b + 1;
  parameter Real b = 2*a;
  parameter Real c = c;
  parameter Real d = a + 1 "reads the cycle without being part of it";
  Real x(start = d, fixed = true);
equation
  der(x) = -x;
end ParameterBindingCycle;
