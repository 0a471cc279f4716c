// Two relative angles over the same pair of flanges, both preferred as states (a
// gearbox's phi_rel and the phi_rel of the elastic element inside it): structurally
// the flanges' accelerations can be the dummy derivatives, but the two constraints
// have the same coefficients for them, so that choice is singular; one of the
// relative angles must give up its state.
model DependentRelativeStates
  Real p1(start = 0, fixed = true) "flange a";
  Real p2 "flange b";
  Real w1(start = 1, fixed = true);
  Real w2;
  Real x(stateSelect = StateSelect.prefer) "relative angle";
  Real y(stateSelect = StateSelect.prefer) "the same relative angle, elsewhere";
  Real xd(stateSelect = StateSelect.prefer);
  Real yd(stateSelect = StateSelect.prefer);
initial equation
  x = 0.1;
  xd = 0;
equation
  x = p2 - p1;
  y = p2 - p1;
  xd = der(x);
  yd = der(y);
  w1 = der(p1);
  w2 = der(p2);
  der(w1) = 10 * y;
  der(w2) = -10 * x;
end DependentRelativeStates;
