model ExperimentMethod "A model that asks for Radau5 in its experiment annotation"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  annotation (experiment(StopTime = 1, __unimo_method = "radau5"));
end ExperimentMethod;
