// expect: E2009 @6:10
partial model Source
  Real y;
end Source;
model Holder
  Source s;
end Holder;
model M
  Holder h;
end M;
