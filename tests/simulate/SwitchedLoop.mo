model SwitchedLoop "if-equation on a discrete Integer inside a nonlinear algebraic loop: Flight-like branch F = 0, contact-like branch D = 0"
  Integer m(start=0, fixed=true);
  Real x(start=1, fixed=true);
  Real F;
  Real D;
  Real y;
equation
  der(x) = D;
  y = D + F + 0.1*sin(y);
  F + 2*y = -x;
  if m == 0 then
    F = 0;
  else
    D = 0;
  end if;
  when time > 0.5 then
    m = 1;
  end when;
end SwitchedLoop;
