model A
  Real x(start = 1);
  Boolean b;
equation
  der(x) = -x;
  b = x < 0.5;
  when b then
    when x < 0.1 then
      reinit(x, 1);
    end when;
  end when;
end A;
