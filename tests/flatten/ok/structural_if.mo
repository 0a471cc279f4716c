model StructuralIf
  parameter Boolean linear = true;
  parameter Integer order = 2;
  Real x(start = 1, fixed = true);
equation
  if linear then
    der(x) = -x;
  else
    der(x) = -x ^ 3;
  end if;
  assert(order > 0, "order must be positive");
end StructuralIf;
