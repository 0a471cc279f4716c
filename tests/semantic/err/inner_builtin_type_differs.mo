// expect: E2035 @4:14
// An inner Integer for an outer Real.
model C
  outer Real T0;
  Real t = T0;
end C;
model M
  inner Integer T0 = 3;
  C c;
end M;
