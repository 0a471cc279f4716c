model SchmittTrigger "An op-amp in positive feedback (the MSL's limited op-amp law with events, strict = false) charging a capacitor: a relaxation oscillator. When the saturated branch of the loop ends at its fold (|v| = 7.499), the relation at its root has no consistent outcome on its own branch: the comparator flips to the other limit at that event"
  parameter Real V0 = 15000;
  parameter Real Vps = 15, Vns = -15;
  parameter Real R = 1000, R1 = 1000, R2 = 1000;
  parameter Real C = 1 / 10 / (2 * R * log(1 + 2 * R1 / R2));
  Real vp "non-inverting input, the divider of the output";
  Real vout(start = -15) "output (the low branch at the start)";
  Real i1 "current through the divider";
  Real v(start = 1, fixed = true) "capacitor voltage, the inverting input";
equation
  vout = smooth(0, if V0 * (vp - v) > Vps then Vps else if V0 * (vp - v) < Vns then Vns else V0 * (vp - v));
  vp = R1 * i1;
  vout - vp = R2 * i1;
  C * der(v) = (vout - v) / R;
  annotation(experiment(StopTime = 0.2, Interval = 1e-4, Tolerance = 1e-6));
end SchmittTrigger;
