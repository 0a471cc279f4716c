// The circuits of NodalCircuits.mo with the capacitor voltages as states (component
// form): independent formulations for tests/singular.rs.

model BridgeRef
  parameter Real C = 1e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 3e3;
  Real vC(start = -0.0, fixed = false) "U1 - U2";
  Real U1, U2, iC;
  Real Ue = sin(2*3.141592653589793*100*time);
initial equation
  U2 = 0;
equation
  C*der(vC) = iC;
  vC = U1 - U2;
  (Ue - U1)/R0 = iC + U1/R1;
  iC = U2/R2;
end BridgeRef;

model CouplingAmplifierRef
  parameter Real C1 = 1e-6, C2 = 2e-6;
  parameter Real R0 = 1e3, R1 = 9e3, R2 = 4e3, R3 = 2e3;
  parameter Real Ub = 6, Is = 1e-14, Ut = 0.026, beta = 0.99;
  Real v1 "U1 - U2";
  Real U3(start = 3.4, fixed = true);
  Real U1, U2(start = 0.66), i1, iD;
  Real Ue = 0.1*sin(2*3.141592653589793*200*time);
initial equation
  U2 = 0.66;
equation
  iD = Is*(exp(U2/Ut) - 1);
  C1*der(v1) = i1;
  v1 = U1 - U2;
  (Ue - U1)/R0 = i1;
  i1 = U2/R1 + (U2 - Ub)/R2 + iD;
  C2*der(U3) = (Ub - U3)/R3 - beta*iD;
end CouplingAmplifierRef;

model FloatingChainRef
  parameter Real C1 = 1e-6, C2 = 3e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 5e3, R3 = 1e3;
  Real v1 "U1 - U2", v2 "U2 - U3";
  Real U1, U2, U3, i1, i2;
  Real Ue = 1 - exp(-time/2e-3) "a smooth step (an input that jumps would move the node voltages chosen as states with it, see docs/backend.md)";
initial equation
  U2 = 0.2;
  U3 = -0.1;
equation
  C1*der(v1) = i1;
  C2*der(v2) = i2;
  v1 = U1 - U2;
  v2 = U2 - U3;
  (Ue - U1)/R0 = i1 + U1/R1;
  i1 = i2 + U2/R2;
  i2 = U3/R3;
end FloatingChainRef;

model TwoFloatingRef
  parameter Real C1 = 1e-6, C2 = 2e-6;
  parameter Real R0 = 1e3, R1 = 2e3, R2 = 3e3, R3 = 1.5e3, R4 = 2.5e3;
  Real v1 "U1 - U2", v2 "U3 - U4";
  Real U1, U2, U3, U4, i1, i2;
  Real Ue = cos(2*3.141592653589793*50*time);
initial equation
  U2 = 0;
  U4 = 0.5;
equation
  C1*der(v1) = i1;
  C2*der(v2) = i2;
  v1 = U1 - U2;
  v2 = U3 - U4;
  (Ue - U1)/R0 = i1 + U1/R1;
  i1 = U2/R2 + (U2 - U3)/R3;
  (U2 - U3)/R3 = i2;
  i2 = U4/R4;
end TwoFloatingRef;

model SeriesLCRef
  parameter Real C = 1e-6, L = 1e-2, R = 50;
  Real uC(start = 0.3, fixed = true);
  Real iL(start = 0, fixed = true);
  Real U1, U2;
  Real Ue = sin(2*3.141592653589793*1000*time);
equation
  C*der(uC) = iL;
  uC = U1 - U2;
  (Ue - U1)/R = iL;
  L*der(iL) = U2;
end SeriesLCRef;
