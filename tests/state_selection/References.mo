// Independent formulations for the dynamic state selection tests (tests/state_selection.rs):
// the same systems in angle coordinates, ordinary differential equations of index 0.

model PendulumAngle "The pendulum of models/PendulumCartesian.mo in its angle"
  parameter Real L = 1;
  parameter Real g = 9.81;
  parameter Real phi0 = 1.5707963267948966;
  parameter Real w0 = 0;
  Real phi(start = phi0, fixed = true);
  Real w(start = w0, fixed = true);
  Real x = L*sin(phi);
  Real y = -L*cos(phi);
equation
  der(phi) = w;
  der(w) = -g/L*sin(phi);
end PendulumAngle;

model DoublePendulumAngles "The double pendulum of models/DoublePendulumCartesian.mo in the angles of its rods (Lagrange's equations)"
  parameter Real L1 = 1;
  parameter Real L2 = 0.8;
  parameter Real m1 = 1;
  parameter Real m2 = 0.5;
  parameter Real g = 9.81;
  parameter Real phi1 = 1.5707963267948966;
  parameter Real phi2 = 3.141592653589793;
  Real a1(start = phi1, fixed = true);
  Real a2(start = phi2, fixed = true);
  Real w1(start = 0, fixed = true);
  Real w2(start = 0, fixed = true);
  Real x1 = L1*sin(a1);
  Real y1 = -L1*cos(a1);
  Real x2 = x1 + L2*sin(a2);
  Real y2 = y1 - L2*cos(a2);
protected
  Real den = 2*m1 + m2 - m2*cos(2*a1 - 2*a2);
equation
  der(a1) = w1;
  der(a2) = w2;
  der(w1) = (-g*(2*m1 + m2)*sin(a1) - m2*g*sin(a1 - 2*a2)
    - 2*sin(a1 - a2)*m2*(w2^2*L2 + w1^2*L1*cos(a1 - a2)))/(L1*den);
  der(w2) = 2*sin(a1 - a2)*(w1^2*L1*(m1 + m2) + g*(m1 + m2)*cos(a1)
    + w2^2*L2*m2*cos(a1 - a2))/(L2*den);
end DoublePendulumAngles;
