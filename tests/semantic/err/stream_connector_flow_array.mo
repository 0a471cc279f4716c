// expect: E2034 @3:11
// The one flow variable of a stream connector is a scalar.
connector FluidPort
  Real p;
  flow Real m_flow[2];
  stream Real h_outflow;
end FluidPort;
model M
  FluidPort port;
end M;
