partial model Base "a first-order lag"
  parameter Real T = 1 "time constant";
  Real x(start = 0, fixed = true);
  Real u "driven by the derived model";
equation
  T * der(x) = u - x;
end Base;

model Inheritance
  extends Base(T = 2, x(start = 1));
  Real y;
equation
  u = sin(time);
  y = 2 * x;
end Inheritance;
