model A
  Real x(start = 1);
equation
  der(x) = -1;
  when x < 0 then
    reinit(x);
  end when;
end A;
