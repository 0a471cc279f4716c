// expect: E2028 @3:14
record R
  inner Real x;
end R;
