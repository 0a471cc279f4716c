// expect: E2036 @10:20
// Connections.root takes an overdetermined variable, not a connector.
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin p;
equation
  Connections.root(p);
end M;
