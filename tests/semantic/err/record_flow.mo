// expect: E2028 @3:13
record R
  flow Real i;
end R;
