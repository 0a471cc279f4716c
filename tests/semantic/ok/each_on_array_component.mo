// `each` on the modifier of an array of components.
model A
  parameter Real k = 1;
  Real y = k;
end A;
model M
  A a[3](each k = 2);
end M;
