// expect: E2034 @3:11
// A stream connector needs exactly one flow variable.
connector FluidPort
  Real p;
  flow Real m_flow;
  flow Real q_flow;
  stream Real h_outflow;
end FluidPort;
model M
  FluidPort port;
end M;
