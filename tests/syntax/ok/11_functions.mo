// Functions: default inputs, protected variables, multiple outputs,
// array inputs of unknown size, recursion, return, while/break,
// and calls with positional and named arguments.
package Functions "Function examples"
  function polyval "Evaluate a polynomial with Horner's scheme"
    input Real c[:] "Coefficients, highest order first";
    input Real x "Abscissa";
    output Real y "Value";
  algorithm
    y := 0;
    for i in 1:size(c, 1) loop
      y := y * x + c[i];
    end for;
    annotation(Inline = true);
  end polyval;

  function minmax "Minimum and maximum of a vector"
    input Real v[:];
    output Real vmin;
    output Real vmax;
  algorithm
    vmin := v[1];
    vmax := v[1];
    for e in v loop
      vmin := min(vmin, e);
      vmax := max(vmax, e);
    end for;
  end minmax;

  function factorial "Recursive factorial"
    input Integer n(min = 0);
    output Integer f;
  algorithm
    if n <= 1 then
      f := 1;
      return;
    end if;
    f := n * factorial(n - 1);
  end factorial;

  function findFirst "Index of the first element above a threshold, 0 if none"
    input Real v[:];
    input Real threshold = 0.5 "Input with a default value";
    output Integer index;
  protected
    Integer i;
  algorithm
    index := 0;
    i := 1;
    while i <= size(v, 1) loop
      if v[i] > threshold then
        index := i;
        break;
      end if;
      i := i + 1;
    end while;
  end findFirst;

  function linspace "n equidistant points between x1 and x2"
    input Real x1;
    input Real x2;
    input Integer n = 5;
    output Real v[n];
  algorithm
    v := {x1 + (x2 - x1) * (i - 1) / (n - 1) for i in 1:n};
  end linspace;
end Functions;

model FunctionUser "Calls the functions"
  parameter Real coeffs[3] = {1, -2, 1};
  parameter Integer fact = Functions.factorial(4);
  parameter Integer idx = Functions.findFirst({0.1, 0.3, 0.7}, threshold = 0.2);
  Real p;
  Real lo;
  Real hi;
  Real pts[5];
  Real c;
equation
  p = Functions.polyval(coeffs, time);
  pts = Functions.linspace(0, time, n = 5);
  c = Functions.polyval(c = {1, 0, 0, 0}, x = time);
algorithm
  (lo, hi) := Functions.minmax({sin(time), cos(time), 0.5});
end FunctionUser;
