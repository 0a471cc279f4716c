model Overflow "y = exp(1000 t) overflows at t = ln(max)/1000"
  Real x(start = 0, fixed = true);
  Real y;
equation
  der(x) = 1000;
  y = exp(x);
  annotation(experiment(StopTime = 1));
end Overflow;
