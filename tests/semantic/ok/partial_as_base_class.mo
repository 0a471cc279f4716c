// A partial class used only as a base class.
partial model Source
  Real y;
end Source;
model Constant
  extends Source;
equation
  y = 1;
end Constant;
model M
  Constant c;
end M;
