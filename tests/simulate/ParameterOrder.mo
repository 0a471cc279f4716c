// A parameter binding that needs a parameter declared further down (the MSL's
// TransferFunction: `x_start[nx] = zeros(nx)` before `nx = size(a, 1) - 1`), and a
// slice with parameter bounds in a scalar product (`a[2:na] * x`: one equation).
model ParameterOrder
  parameter Real a[:] = {1, 3, 2};
  parameter Real x_start[size(a, 1) - 1] = zeros(nx);
  Real x[nx](start = x_start, each fixed = true);
  Real y;
protected
  parameter Integer na = size(a, 1);
  parameter Integer nx = size(a, 1) - 1;
equation
  der(x[1]) = 1 - a[2:na] * x;
  der(x[2:nx]) = x[1:nx - 1];
  y = a[2:na] * x;
  annotation(experiment(StopTime = 1));
end ParameterOrder;
