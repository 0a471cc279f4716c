// `pre` of a Real assigned in a when clause, and of a `discrete` Real, outside when.
model M
  discrete Real d(start = 0, fixed = true);
  Real s(start = 0, fixed = true);
  Real x(start = 0, fixed = true);
  Real y;
  Real z;
equation
  der(x) = 1;
  when sample(0, 0.1) then
    s = x;
    d = pre(d) + 1;
  end when;
  y = pre(s);
  z = pre(d);
end M;
