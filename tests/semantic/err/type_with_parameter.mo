// expect: E2027 @3:18
type T
  parameter Real k = 1;
end T;
