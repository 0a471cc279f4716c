// A `final` modifier set in a modification, and the non-final one beside it changed.
model A
  parameter Real k = 1;
  parameter Real g = 2;
  Real y = k + g;
end A;
model B
  A a(final k = 3);
end B;
model M
  B b(a(g = 4));
end M;
