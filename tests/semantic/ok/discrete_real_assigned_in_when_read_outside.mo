// A discrete Real assigned in a when clause may give its value to a continuous Real.
model M
  discrete Real y_last(start = 0, fixed = true);
  Real y;
equation
  when sample(0, 0.1) then
    y_last = time;
  end when;
  y = y_last;
end M;
