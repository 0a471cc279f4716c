// Equation section forms: simple and implicit equations, array equations,
// nested and multi-index for-equations, assert and terminate.
model EquationsDemo
  parameter Integer n = 3;
  parameter Integer m = 2;
  Real x(start = 1, fixed = true) "Decaying state";
  Real y "Defined implicitly";
  Real z[n];
  Real M[n, m];
  Real P[n, n];
  Real s;
  Real w[2];
equation
  der(x) = -x;
  y + 2 * x = 3;
  for i in 1:n loop
    z[i] = i * x;
  end for;
  for i in 1:n, j in 1:m loop
    M[i, j] = i + j * y;
  end for;
  for i in 1:n loop
    for j in 1:n loop
      P[i, j] = if i == j then z[i] else 0;
    end for;
  end for;
  0 = s - sum(z);
  w = {x, y} * 2 "Array equation";
  assert(x > 0, "x must stay positive");
  assert(y < 100, "y unexpectedly large", AssertionLevel.warning);
  when x < 0.1 then
    terminate("x decayed below 0.1");
  end when;
end EquationsDemo;

model FunctionCallEquations "Equations whose right-hand side is a call"
  Real r = sqrt(2.0);
  Real angle;
  Real t;
equation
  angle = atan2(1.0, r);
  t = tan(angle) "Equation with a description";
  assert(abs(t) < 1e3, "angle too close to pi/2");
end FunctionCallEquations;
