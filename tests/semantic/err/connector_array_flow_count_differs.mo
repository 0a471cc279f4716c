// expect: E2037 @3:11
// Scalars are counted: two potential, three flow.
connector Plug
  Real v[2];
  flow Real i[3];
end Plug;
model M
  Plug p;
end M;
