// `reinit` inside `when`, `edge` of a Boolean, `pre` of a discrete variable.
model M
  Real x(start = 1, fixed = true);
  Boolean b = x < 0.5;
  discrete Integer n(start = 0, fixed = true);
equation
  der(x) = -x;
  when edge(b) then
    reinit(x, 1);
    n = pre(n) + 1;
  end when;
end M;
