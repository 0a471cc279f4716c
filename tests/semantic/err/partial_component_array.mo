// expect: E2009 @6:10
partial model Source
  Real y;
end Source;
model M
  Source s[2];
end M;
