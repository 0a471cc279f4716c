// Modifying a public parameter of a class that also has protected ones.
model A
  parameter Real k = 1;
  Real y = k*g;
protected
  parameter Real g = 2;
end A;
model M
  A a(k = 3);
end M;
