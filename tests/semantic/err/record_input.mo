// expect: E2028 @3:14
record R
  input Real x;
end R;
