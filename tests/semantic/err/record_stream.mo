// expect: E2028 @3:15
record R
  stream Real h;
end R;
