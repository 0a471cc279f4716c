// expect: E2028 @3:13
model M
  flow Real i = 1;
end M;
