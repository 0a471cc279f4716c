// expect: E2027 @6:5
model A
  Real y = 1;
end A;
record R
  A a[2];
end R;
