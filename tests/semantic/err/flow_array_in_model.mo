// expect: E2028 @3:13
model M
  flow Real i[2] = {1, 2};
end M;
