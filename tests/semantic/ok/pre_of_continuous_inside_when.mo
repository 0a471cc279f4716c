// `pre` of a continuous Real inside a when clause.
model M
  Real x(start = 0, fixed = true);
  discrete Real last(start = 0, fixed = true);
equation
  der(x) = 1;
  when x > 0.5 then
    last = pre(x);
  end when;
end M;
