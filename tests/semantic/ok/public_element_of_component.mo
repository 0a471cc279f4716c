// Public elements of a component, also when its class has protected ones.
model A
  Real y = 2*k;
protected
  parameter Real k = 1;
end A;
model M
  A a;
  Real z = a.y;
end M;
