// expect: E2028 @3:14
record R
  outer Real x;
end R;
