model Mass
  parameter Real m = 1;
  Real x(start = 0, fixed = true), v(start = 0, fixed = true);
  Real f;
equation
  der(x) = v;
  m * der(v) = f;
end Mass;

model ComponentArrays
  parameter Integer n = 3;
  Mass masses[n](each m = 2);
equation
  for i in 1:n loop
    masses[i].f = -masses[i].x + i;
  end for;
end ComponentArrays;
