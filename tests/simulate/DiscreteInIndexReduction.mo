model DiscreteInIndexReduction
  "index reduction through an equation of a discrete variable (MSL KinematicPTP2: noWphase):
   der(s) needs the equation of s2, which reads b; b = a >= 1 is differentiated too, and its
   derivative, identically zero, stands as der(b) = 0. s = t/2, sd = 1/2, x = t/2."
  parameter Real a = 1;
  Boolean b;
  Real s2, s, sd, x(start = 0, fixed = true);
equation
  b = a >= 1;
  s2 = if b then 0.5 else 0;
  s = s2 * time;
  sd = der(s);
  der(x) = sd;
end DiscreteInIndexReduction;
