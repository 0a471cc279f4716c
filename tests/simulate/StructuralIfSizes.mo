model StructuralIfSizes "A binding whose branches have different sizes, chosen by a parameter (the MSL's BooleanTable); matrix rows built from vectors as columns"
  parameter Real t[:] = {2, 4};
  parameter Integer n = size(t, 1);
  parameter Real m[:, :] = if n > 0 then [t[1], 1.0; t, {3, 5}] else [0.0, 0.0];
  Real y;
equation
  y = sum(m) * time;
end StructuralIfSizes;
