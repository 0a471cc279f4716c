// `annotation(Evaluate = true)`: the parameter's value is fixed at translation, and so
// are the parameters bound to it alone. A capacitance of 0 removes the capacitor's
// derivative (the MSL's HeatingNPN_NORGate sets all its capacitances so): v2 is then
// the divider's 2/3 of v1.
model EvaluatedParameters
  parameter Real C0 = 0 annotation(Evaluate = true);
  parameter Real C = C0 "bound to the evaluated parameter alone";
  parameter Real R2 = 2 "not evaluated: stays a parameter";
  Real x(start = 1, fixed = true);
  Real v1, v2, i;
equation
  der(x) = -x;
  v1 = x;
  v1 - v2 = i + v2 / R2;
  i = C * der(v2);
  annotation(experiment(StopTime = 1));
end EvaluatedParameters;
