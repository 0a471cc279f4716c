model DoublePendulum "Two point masses on rigid rods, Cartesian coordinates: index 3"
  parameter Real L1 = 1;
  parameter Real L2 = 0.8;
  parameter Real m1 = 1;
  parameter Real m2 = 0.5;
  parameter Real g = 9.81;
  Real x1(start = 0.6, fixed = true), y1(start = -0.8);
  Real x2(start = 0.6 + 0.8, fixed = true), y2(start = -0.8);
  Real vx1(start = 0, fixed = true), vy1, vx2(start = 0, fixed = true), vy2;
  Real F1 "Force per length in rod 1";
  Real F2 "Force per length in rod 2";
equation
  der(x1) = vx1;
  der(y1) = vy1;
  der(x2) = vx2;
  der(y2) = vy2;
  m1*der(vx1) = -F1*x1 + F2*(x2 - x1);
  m1*der(vy1) = -F1*y1 + F2*(y2 - y1) - m1*g;
  m2*der(vx2) = -F2*(x2 - x1);
  m2*der(vy2) = -F2*(y2 - y1) - m2*g;
  x1^2 + y1^2 = L1^2;
  (x2 - x1)^2 + (y2 - y1)^2 = L2^2;
end DoublePendulum;
