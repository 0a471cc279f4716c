// expect: E2027 @3:8
type T
  Real x;
end T;
