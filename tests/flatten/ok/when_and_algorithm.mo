model WhenAndAlgorithm
  Real h(start = 1, fixed = true), v(start = 0, fixed = true);
  discrete Integer bounces(start = 0, fixed = true);
  Real y;
equation
  der(h) = v;
  der(v) = -9.81;
  when h < 0 then
    reinit(v, -0.8 * pre(v));
    bounces = pre(bounces) + 1;
  end when;
algorithm
  y := 0;
  for i in 1:3 loop
    y := y + i * h;
  end for;
end WhenAndAlgorithm;
