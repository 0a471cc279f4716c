// `each` on an array member of a scalar component.
model A
  parameter Real k[3] = {1, 2, 3};
  Real y = sum(k);
end A;
model M
  A a(k(each min = 0));
end M;
