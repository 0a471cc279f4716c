model FixedDelaySine "Modelica.Blocks.Nonlinear.FixedDelay of a sine (the MSL beside the project)"
  Modelica.Blocks.Sources.Sine sine(f = 1, amplitude = 2);
  Modelica.Blocks.Nonlinear.FixedDelay fixedDelay(delayTime = 0.3);
  Modelica.Blocks.Nonlinear.VariableDelay variableDelay(delayMax = 1);
  Modelica.Blocks.Sources.Ramp ramp(height = 0.5, duration = 2, offset = 0.2);
equation
  connect(sine.y, fixedDelay.u);
  connect(sine.y, variableDelay.u);
  connect(ramp.y, variableDelay.delayTime);
  annotation(experiment(StopTime = 2, Tolerance = 1e-8));
end FixedDelaySine;
