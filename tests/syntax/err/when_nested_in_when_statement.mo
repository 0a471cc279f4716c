model A
  Real x(start = 1);
  discrete Real y;
equation
  der(x) = -x;
algorithm
  when x < 0.5 then
    when x < 0.1 then
      y := 1;
    end when;
  end when;
end A;
