// `each` inside the modifier of an element of an array of components.
model A
  parameter Real k = 1;
  Real y = k;
end A;
model B
  A a;
end B;
model M
  B b[2](a(each k = 3));
end M;
