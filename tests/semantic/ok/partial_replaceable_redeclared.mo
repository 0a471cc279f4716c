// A replaceable component of a partial class, redeclared with a complete one.
partial model Source
  Real y;
end Source;
model Constant
  extends Source;
equation
  y = 1;
end Constant;
model Holder
  replaceable Constant s constrainedby Source;
end Holder;
model M
  Holder h(redeclare Constant s);
end M;
