function fib "Fibonacci by a loop"
  input Integer n;
  output Integer f;
protected
  Integer a = 0, b = 1, t;
algorithm
  for i in 1:n loop
    t := a + b;
    a := b;
    b := t;
  end for;
  f := a;
end fib;

function firstAbove "index of the first element above a threshold"
  input Real v[:];
  input Real threshold = 0.5;
  output Integer k;
algorithm
  k := 0;
  for i in 1:size(v, 1) loop
    if v[i] > threshold then
      k := i;
      return;
    end if;
  end for;
end firstAbove;

model FunctionEvaluation "sizes computed by user functions at compile time"
  parameter Integer n = fib(6) "8";
  Real x[n](each start = 1, each fixed = true);
  Real y[integer(Modelica.Math.Vectors.norm({3, 4}))] "5";
  Real z[firstAbove({0.1, 0.2, 0.9, 2}, threshold = 0.15)] "2";
equation
  der(x) = -x;
  y = fill(time, 5);
  z = {1, 2};
end FunctionEvaluation;
