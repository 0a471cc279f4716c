function f
  input Real x;
  output Real y;
algorithm
  when x > 0 then
    y := 1;
  end when;
end f;
