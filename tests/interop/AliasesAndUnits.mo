model AliasesAndUnits "Aliases, a negated alias, a parameter alias and units in result files"
  parameter Real k(unit = "1/s") = 2 "Decay rate";
  parameter Integer n = 3 "Sets an array size";
  final parameter Real c = 1.5 "A final parameter";
  parameter Boolean on = true "A switch";
  type Mode = enumeration(slow, fast);
  parameter Mode mode = Mode.slow "An enumeration";
  Real x(start = 1, fixed = true, unit = "m") "Position";
  Real y(unit = "m") "Same as x";
  Real z "Minus x";
  Real w "Equal to k";
  Real a[n];
equation
  der(x) = -k * x * (if on then 1 else 0.5) * (if mode == Mode.fast then 2 else 1);
  y = x;
  z = -y;
  w = k;
  for i in 1:n loop
    a[i] = i * x + c;
  end for;
  annotation(experiment(StopTime = 1));
end AliasesAndUnits;
