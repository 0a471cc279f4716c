model LeverWithLength "a lever angle phi and a length s = L cos(phi) that depends on it, both prefer'd as states; phi's start is fixed, and s is stationary in phi where the lever starts"
  parameter Real L = 1;
  parameter Real d = 0.1 "damping on the length's rate";
  Real phi(start = 0, fixed = true, stateSelect = StateSelect.prefer);
  Real w(start = 1, fixed = true, stateSelect = StateSelect.prefer);
  Real s(stateSelect = StateSelect.prefer);
  Real v(stateSelect = StateSelect.prefer);
  Real z "a function of the length, differentiated (default priority): the choice among phi, s and z is static";
equation
  der(phi) = w;
  s = L*cos(phi);
  v = der(s);
  z = s^3 + s;
  der(w) = -sin(phi) - d*v + 1e-3*der(z);
  annotation(experiment(StopTime = 10));
end LeverWithLength;

model LeverReference "the same motion in the angle alone (an ODE): v = -L sin(phi) w, der(z) = (3 s^2 + 1) v"
  parameter Real L = 1;
  parameter Real d = 0.1;
  Real phi(start = 0, fixed = true);
  Real w(start = 1, fixed = true);
equation
  der(phi) = w;
  der(w) = -sin(phi) + (1e-3*(3*(L*cos(phi))^2 + 1) - d)*(-L*sin(phi)*w);
end LeverReference;

model LeverAliased "MSL's Parts.RollingWheel pattern: the part declares its angle `always` and equates it with its joint's, declared `avoid`; the joint's angle is the alias set's representative"
  parameter Real L = 1;
  parameter Real d = 0.1;
  Real angle(start = 0, fixed = true, stateSelect = StateSelect.always) "the part's";
  Real phi(stateSelect = StateSelect.avoid) "the joint's";
  Real w(start = 1, fixed = true, stateSelect = StateSelect.prefer);
  Real s(stateSelect = StateSelect.prefer);
  Real v(stateSelect = StateSelect.prefer);
  Real z;
equation
  angle = phi;
  der(phi) = w;
  s = L*cos(phi);
  v = der(s);
  z = s^3 + s;
  der(w) = -sin(phi) - d*v + 1e-3*der(z);
end LeverAliased;
