// expect: E2034 @3:11
// A stream connector without any flow variable.
connector FluidPort
  Real p;
  stream Real h_outflow;
end FluidPort;
model M
  FluidPort port;
end M;
