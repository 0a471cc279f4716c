// Connected variables must agree in flow prefix, size and type: a Boolean potential
// does not connect to a Real one, an enumeration only to the same enumeration.
type Mode = enumeration(Off, On);
type Level = enumeration(Low, High);
connector Pin
  Real v;
  flow Real i;
end Pin;
connector Switch
  Boolean v;
  flow Real i;
end Switch;
connector Plain
  Real v;
  Real i;
end Plain;
connector Pin3
  Real v[3];
  flow Real i[3];
end Pin3;
connector Pin2
  Real v[2];
  flow Real i[2];
end Pin2;
connector ModePort
  Mode m;
end ModePort;
connector LevelPort
  Level m;
end LevelPort;
model ConnectorTypes
  Pin p;
  Switch s;
  Plain q;
  Pin3 p3;
  Pin2 p2;
  ModePort a;
  LevelPort b;
equation
  connect(p, s);
  connect(p, q);
  connect(p3, p2);
  connect(a, b);
end ConnectorTypes;
