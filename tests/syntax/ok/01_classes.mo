// One class of each restricted kind, several classes in one file,
// partial and encapsulated classes, and class description strings.
within;

type Voltage = Real(unit = "V", quantity = "ElectricPotential") "Electric potential";

connector Port "A simple acausal port"
  Voltage v "Potential at the port";
  flow Real i(unit = "A") "Current flowing into the port";
end Port;

record Parameters "Physical parameters of an oscillator"
  Real m = 1.0 "Mass";
  Real k = 10.0 "Spring constant";
end Parameters;

function square "Square of a number"
  input Real x;
  output Real y;
algorithm
  y := x * x;
end square;

partial model PartialOscillator "Common declarations of oscillators"
  parameter Parameters p "Parameter record";
  Real x(start = 1, fixed = true) "Position";
  Real v(start = 0, fixed = true) "Velocity";
end PartialOscillator;

model Oscillator "Undamped spring-mass oscillator"
  extends PartialOscillator;
equation
  der(x) = v;
  p.m * der(v) = -p.k * x;
end Oscillator;

block Gain "Output is the input multiplied by a constant"
  parameter Real k = 2 "Gain";
  input Real u "Input signal";
  output Real y "Output signal";
equation
  y = k * u;
end Gain;

encapsulated package Util "An encapsulated package: lookup stops here"
  constant Real pi = 3.14159265358979;

  function circleArea "Area of a circle"
    input Real r;
    output Real a;
  algorithm
    a := pi * r ^ 2;
  end circleArea;
end Util;

model UseAll "Instantiates the classes above"
  Oscillator osc(p(m = 2.0, k = 8.0));
  Gain g(k = 3, u = osc.x);
  Real e;
equation
  e = square(g.y) + Util.circleArea(1.0);
end UseAll;
