model A
  Real x(start = 1);
equation
  der(x) = -1;
  when x < 0 then
    reinit(2 * x, 0);
  end when;
end A;
