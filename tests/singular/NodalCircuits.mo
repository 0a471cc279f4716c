// Circuits in nodal form whose capacitors connect nodes without a capacitive path to
// ground: structurally regular, but the coefficient matrix of the node voltages'
// derivatives is singular (a hidden algebraic constraint). References in
// CapacitorStates.mo (the same circuits with the capacitor voltages as states).

model Bridge "A capacitor between two nodes, resistors to ground"
  parameter Real C = 1e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 3e3;
  Real U1, U2(start = 0, fixed = true);
  Real Ue = sin(2*3.141592653589793*100*time);
equation
  (Ue - U1)/R0 = C*der(U1 - U2) + U1/R1;
  C*der(U1 - U2) = U2/R2;
end Bridge;

model CouplingAmplifier "Coupling capacitor into a diode-loaded base node driving a transistor-like current into a collector node with a capacitor to ground"
  parameter Real C1 = 1e-6, C2 = 2e-6;
  parameter Real R0 = 1e3, R1 = 9e3, R2 = 4e3, R3 = 2e3;
  parameter Real Ub = 6, Is = 1e-14, Ut = 0.026, beta = 0.99;
  Real U1, U2(start = 0.66, fixed = true), U3(start = 3.4, fixed = true);
  Real iD "Base-emitter diode current";
  Real Ue = 0.1*sin(2*3.141592653589793*200*time);
equation
  iD = Is*(exp(U2/Ut) - 1);
  (Ue - U1)/R0 = C1*der(U1 - U2);
  C1*der(U1 - U2) = U2/R1 + (U2 - Ub)/R2 + iD;
  C2*der(U3) = (Ub - U3)/R3 - beta*iD;
end CouplingAmplifier;

model FloatingChain "Two capacitors in series between three nodes, none to ground"
  parameter Real C1 = 1e-6, C2 = 3e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 5e3, R3 = 1e3;
  Real U1, U2(start = 0.2, fixed = true), U3(start = -0.1, fixed = true);
  Real Ue = 1 - exp(-time/2e-3) "a smooth step (an input that jumps would move the node voltages chosen as states with it, see docs/backend.md)";
equation
  (Ue - U1)/R0 = C1*der(U1 - U2) + U1/R1;
  C1*der(U1 - U2) = C2*der(U2 - U3) + U2/R2;
  C2*der(U2 - U3) = U3/R3;
end FloatingChain;

model TwoFloating "Two separate floating capacitors: two hidden constraints"
  parameter Real C1 = 1e-6, C2 = 2e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 3e3, R3 = 1.5e3, R4 = 2.5e3;
  Real U1, U2(start = 0, fixed = true), U3, U4(start = 0.5, fixed = true);
  Real Ue = cos(2*3.141592653589793*50*time);
equation
  (Ue - U1)/R0 = C1*der(U1 - U2) + U1/R1;
  C1*der(U1 - U2) = U2/R2 + (U2 - U3)/R3;
  (U2 - U3)/R3 = C2*der(U3 - U4);
  C2*der(U3 - U4) = U4/R4;
end TwoFloating;

model SeriesLC "A floating capacitor in series with an inductor to ground"
  parameter Real C = 1e-6, L = 1e-2, R = 50;
  Real U1, U2, iL(start = 0, fixed = true);
  Real uC(start = 0.3, fixed = true) "Capacitor voltage";
  Real Ue = sin(2*3.141592653589793*1000*time);
equation
  uC = U1 - U2;
  (Ue - U1)/R = C*der(U1 - U2);
  C*der(U1 - U2) = iL;
  L*der(iL) = U2;
end SeriesLC;
