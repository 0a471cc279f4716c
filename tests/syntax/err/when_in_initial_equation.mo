model A
  Real x;
initial equation
  when time > 1 then
    x = 1;
  end when;
equation
  der(x) = 0;
end A;
