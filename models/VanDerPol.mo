model VanDerPol "VDPOL: Van der Pol oscillator in the stiff scaling of the test set, eps = 1e-6"
  parameter Real eps = 1e-6;
  Real y1(start = 2, fixed = true);
  Real y2(start = 0, fixed = true);
equation
  der(y1) = y2;
  der(y2) = ((1 - y1^2)*y2 - y1)/eps;
  annotation(experiment(StopTime = 2, Tolerance = 1e-6));
end VanDerPol;
