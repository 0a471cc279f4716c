// Index 2: a capacitor directly across an ideal voltage source; its voltage is given,
// so its charge is not a state and the current follows from differentiating v = u(t).
model CapacitorOnSource
  parameter Real C = 1e-3;
  parameter Real R = 100;
  parameter Real f = 50;
  Real u "Source voltage";
  Real v "Capacitor voltage";
  Real i "Capacitor current";
  Real iR "Resistor current";
  Real iS "Source current";
equation
  u = sin(2*3.141592653589793*f*time);
  v = u;
  C*der(v) = i;
  R*iR = u;
  iS = i + iR;
end CapacitorOnSource;
