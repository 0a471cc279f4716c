model Circle "A point going round the unit circle: x^2 + y^2 = 1 is an invariant while time < 5 (projected), and drifts after"
  Real x(start = 1, fixed = true);
  Real y(start = 0, fixed = true);
  Real w(start = 0.5, fixed = true) "Not in the invariant: left alone by the projection";
  Real r2 = x^2 + y^2 - 1 "0 on the circle";
  Boolean on = time < 5 "The invariant is declared";
equation
  der(x) = -y;
  der(y) = x;
  der(w) = -w;
  if time < 5 then
    Unimo.invariant(x^2 + y^2 - 1);
  end if;
end Circle;
