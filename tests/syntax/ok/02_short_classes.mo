// Short class definitions: types, connectors, records and models defined
// as modified or re-prefixed versions of other classes.
type Length = Real(unit = "m", quantity = "Length");
type Mass = Real(final unit = "kg", min = 0) "Mass in kilograms";
type Position3 = Real[3](each unit = "m") "Position vector";
type Count = Integer(min = 0);
type Flag = Boolean;
type Label = String "A text label";

connector RealInput = input Real "Real input signal";
connector RealOutput = output Real "Real output signal";
connector BooleanOutput = output Boolean;

record Point "Point in the plane"
  Length x = 0;
  Length y = 0;
end Point;

record UnitPoint = Point(x = 1, y = 1) "A point at (1, 1)";

model Spring "Linear spring force"
  parameter Real c = 1 "Stiffness";
  Length s "Elongation";
  Real f "Force";
equation
  f = c * s;
end Spring;

model StiffSpring = Spring(c = 1e4) "A much stiffer spring";

block Integrator "Integrates its input"
  RealInput u;
  RealOutput y(start = 0, fixed = true);
equation
  der(y) = u;
end Integrator;

block Threshold "True while the input exceeds a limit"
  parameter Real limit = 0.5;
  RealInput u;
  BooleanOutput active;
equation
  active = u > limit;
end Threshold;

model ShortClassUser "Uses the short classes"
  parameter Length l = 2.5;
  parameter Mass m = 3;
  parameter Position3 r = {1, 2, 3};
  parameter Count n = 4;
  parameter Flag verbose = false;
  parameter Label name = "demo";
  StiffSpring sp(s = l * sin(time));
  UnitPoint corner;
  Integrator integ(u = sp.f / m);
  Threshold th(limit = 0.1, u = integ.y);
end ShortClassUser;
