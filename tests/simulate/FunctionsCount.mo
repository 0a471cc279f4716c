model FunctionsCount "Functions with algorithm sections, several outputs, records in and out and a while loop: balance and closed form"
  record State
    Real p;
    Real v;
  end State;
  function polar "several outputs, algorithm"
    input Real x;
    input Real y;
    output Real r;
    output Real phi;
  algorithm
    r := sqrt(x^2 + y^2);
    phi := atan2(y, x);
  end polar;
  function step "record in, record out"
    input State s;
    input Real k;
    output State d;
  protected
    Real a;
  algorithm
    a := -k*s.p;
    d := State(p = s.v, v = a);
  end step;
  function sumTo "while loop"
    input Integer n;
    output Real s;
  protected
    Integer i;
  algorithm
    s := 0;
    i := 1;
    while i <= n loop
      s := s + i;
      i := i + 1;
    end while;
  end sumTo;
  parameter Real k = 4;
  Real x(start = 1, fixed = true), y(start = 0, fixed = true);
  Real r, phi;
  State s(p(start = 1, fixed = true), v(start = 0, fixed = true));
  State ds;
  Real total = sumTo(4);
equation
  der(x) = -y;
  der(y) = x;
  (r, phi) = polar(x, y);
  ds = step(s, k);
  der(s.p) = ds.p;
  der(s.v) = ds.v;
end FunctionsCount;
