// Enumeration types, enumeration literals with descriptions,
// comparisons and enumeration-valued parameters and variables.
type Color = enumeration(
    Red "Stop",
    Yellow "Prepare",
    Green "Go") "Traffic light colors";

type Mode = enumeration(Off, Heating, Cooling) "Operating modes";

model TrafficLight "Cycles through the colors"
  parameter Real period = 10 "Time between changes";
  discrete Color c(start = Color.Red, fixed = true) "Current color";
  Boolean go "True when cars may drive";
equation
  when sample(0, period) then
    c = if pre(c) == Color.Red then Color.Green
        elseif pre(c) == Color.Green then Color.Yellow
        else Color.Red;
  end when;
  go = c == Color.Green;
end TrafficLight;

model Thermostat "Heating and cooling controlled by an enumeration"
  parameter Mode initialMode = Mode.Off;
  parameter Real T_set = 293.15;
  parameter Real band = 1;
  Real T(start = 295, fixed = true) "Room temperature";
  discrete Mode mode(start = initialMode, fixed = true);
  Real Q;
equation
  when T < T_set - band then
    mode = Mode.Heating;
  elsewhen T > T_set + band then
    mode = Mode.Cooling;
  end when;
  Q = if mode == Mode.Heating then 100 elseif mode == Mode.Cooling then -100 else 0;
  100 * der(T) = Q + 2 * (280 - T);
end Thermostat;

model EnumCompare "Relational operators on enumerations"
  parameter Color a = Color.Yellow;
  Boolean warm = a > Color.Red and a <= Color.Green;
  Boolean notRed = a <> Color.Red;
end EnumCompare;
