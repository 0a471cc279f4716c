package Folding "Parameter folding (tests/fold.rs): what a known parameter value removes"
  model Switches "A friction-like term, an if-branch and a relation on parameters"
    parameter Real mu = 0 "Friction coefficient: 0 removes the friction term";
    parameter Boolean useSpring = false "false: the spring's branch cannot be taken";
    parameter Real limit = 2 "A relation of parameters only: never an event";
    parameter Real c = 4 "Stiffness";
    parameter Real g = 9.81;
    Real x(start = 1, fixed = true);
    Real v(start = 0, fixed = true);
    Real f "Friction force";
    Boolean slipping "Changes with v unless mu = 0";
  equation
    der(x) = v;
    slipping = mu > 0 and abs(v) > 1e-3;
    f = if slipping then -mu * g * sign(v) else -mu * v;
    der(v) = f + (if useSpring then -c * x else -x) + (if limit > 1 then 0 else 1);
  end Switches;

  model Initial "fixed = false parameters are computed at initialization: never folded"
    parameter Real a(fixed = false);
    parameter Real b = 2 * a "follows a: not folded either";
    parameter Real k = 3;
    Real x(start = 1, fixed = true);
  initial equation
    a = k + 1;
  equation
    der(x) = -b * x;
  end Initial;
end Folding;
