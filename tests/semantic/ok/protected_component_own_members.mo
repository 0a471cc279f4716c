// A class reads public members of its own protected component.
model A
  Real y = 1;
end A;
model M
  Real z = a.y;
protected
  A a;
end M;
