// Inheritance with 'extends' and modifiers: value modifiers, nested
// attribute modifiers, 'final' and 'each', and annotations on extends.
partial model FirstOrderBase "Base of first-order systems"
  parameter Real T(min = 0) = 1 "Time constant";
  parameter Real k = 1 "Gain";
  Real y(start = 0, fixed = true) "Output";
  Real u "Input";
end FirstOrderBase;

model FirstOrder "First-order lag"
  extends FirstOrderBase;
equation
  T * der(y) = k * u - y;
end FirstOrder;

partial model Named "Adds a name"
  parameter String label = "unnamed";
end Named;

model Sine "Sine signal"
  parameter Real amplitude = 1;
  parameter Real f = 1 "Frequency";
  Real y;
equation
  y = amplitude * sin(2 * 3.14159265 * f * time);
end Sine;

model Filter "Multiple inheritance with modifiers"
  extends FirstOrder(final k = 2, T(min = 1e-3) = 0.2, y(start = 0.5, nominal = 1.0))
    annotation(Documentation(info = "Modified base class"));
  extends Named(label = "filter");
  Sine src(amplitude = 2, f = 0.5);
equation
  u = src.y;
end Filter;

model FilterBank "Arrays of components with 'each' modifiers"
  parameter Integer n = 3;
  FirstOrder stage[n](each k = 1, T = {0.1, 0.2, 0.4}, each y(start = 0, fixed = true));
  Sine src(final f = 2);
equation
  stage[1].u = src.y;
  for i in 2:n loop
    stage[i].u = stage[i - 1].y;
  end for;
end FilterBank;

model SlowFilter = Filter(T = 5, src(amplitude = 0.5)) "Short class with nested modifiers";
