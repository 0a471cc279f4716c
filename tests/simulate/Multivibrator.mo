model Multivibrator "An op-amp in positive feedback (the MSL's limited op-amp law under noEvent, no events) charging a capacitor: the loop has two solutions between the folds at v = -+7.499 and keeps the branch it is on until that branch ends"
  parameter Real V0 = 15000;
  parameter Real Vps = 15, Vns = -15;
  parameter Real R = 1000, R1 = 1000, R2 = 1000;
  parameter Real C = 1 / 10 / (2 * R * log(1 + 2 * R1 / R2));
  Real vp "non-inverting input, the divider of the output";
  Real vout(start = -15) "output (the low branch at the start)";
  Real i1 "current through the divider";
  Real v(start = 1, fixed = true) "capacitor voltage, the inverting input";
equation
  vout = smooth(0, noEvent(if V0 * (vp - v) > Vps then Vps else if V0 * (vp - v) < Vns then Vns else V0 * (vp - v)));
  vp = R1 * i1;
  vout - vp = R2 * i1;
  C * der(v) = (vout - v) / R;
  annotation(experiment(StopTime = 0.2, Interval = 1e-4, Tolerance = 1e-6));
end Multivibrator;
