// initial equation and initial algorithm sections, fixed = false
// parameters computed during initialization, steady-state initialization.
model InitialEquations "Initial values from initial equations"
  parameter Real x0 = 2 "Initial position";
  parameter Real k(fixed = false) "Computed during initialization";
  Real x "Position";
  Real v "Velocity";
initial equation
  x = x0;
  der(v) = 0 "Start in steady state for v";
  k = 2 * x0;
equation
  der(x) = v;
  der(v) = -k * x - v + 1;
end InitialEquations;

model InitialAlgorithm "Initial values from an initial algorithm"
  parameter Integer n = 3;
  Real x[n] "States";
initial algorithm
  for i in 1:n loop
    x[i] := i * 0.5;
  end for;
equation
  der(x) = -x;
end InitialAlgorithm;

model MixedInitialization "Both kinds of initial sections in one model"
  parameter Real T0 = 300;
  Real T(start = T0) "Temperature";
  Real h "Enthalpy";
  discrete Integer phase(start = 1, fixed = true);
initial algorithm
  assert(T0 > 0, "T0 must be positive");
initial equation
  T = T0 + 5;
equation
  h = 4186 * T;
  der(T) = (290 - T) / 100;
  when T < 300 then
    phase = 2;
  end when;
end MixedInitialization;
