// A protected element of a base class used unqualified in the subclass.
model Base
protected
  parameter Real k = 2;
end Base;
model M
  extends Base;
  Real y = k;
end M;
