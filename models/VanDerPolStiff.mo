model VanDerPolStiff "Van der Pol oscillator x'' - mu*(1 - x^2)*x' + x = 0 with mu = 1e6"
  parameter Real mu = 1e6;
  Real x(start = 2, fixed = true);
  Real v(start = 0, fixed = true);
equation
  der(x) = v;
  der(v) = mu*(1 - x^2)*v - x;
  annotation(experiment(StopTime = 2e6, Tolerance = 1e-6));
end VanDerPolStiff;
