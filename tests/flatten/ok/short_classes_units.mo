model ShortClassesUnits
  import SI = Modelica.SIunits;
  type Gain = Real(unit = "1", min = 0);
  type BigGain = Gain(max = 100);
  parameter BigGain g = 3;
  SI.Length s(start = 1, fixed = true);
  SI.Velocity v;
equation
  der(s) = v;
  v = -g * s;
end ShortClassesUnits;
