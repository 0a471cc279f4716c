// `each` on a public parameter of an array of components with protected parts.
model A
  parameter Real k = 1;
  Real y = k*g;
protected
  parameter Real g = 2;
end A;
model M
  A a[2](each k = 2);
end M;
