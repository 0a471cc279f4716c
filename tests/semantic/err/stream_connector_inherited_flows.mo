// expect: E2034 @7:11
// Inherited flow variables count too: two in all.
partial connector Base
  Real p;
  flow Real m_flow;
end Base;
connector FluidPort
  extends Base;
  flow Real q_flow;
  stream Real h_outflow;
end FluidPort;
model M
  FluidPort port;
end M;
