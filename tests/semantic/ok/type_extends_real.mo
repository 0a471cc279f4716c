// Types derived from predefined types, and from other types.
type Angle = Real(unit = "rad");
type Speed = Real(unit = "m/s");
model M
  Angle phi = 1;
  Speed v = 2;
end M;
