// expect: E2028 @3:14
record R
  input Real x[3];
end R;
