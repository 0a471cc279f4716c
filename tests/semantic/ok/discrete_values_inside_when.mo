// Inside a when clause every expression is discrete-time.
model M
  Real x = time;
  Integer i(start = 0, fixed = true);
  Boolean b(start = false, fixed = true);
equation
  when sample(0, 0.5) then
    i = integer(x) + 1;
    b = noEvent(x > 1);
  end when;
end M;
