// The one flow variable of a stream connector may be inherited.
partial connector Base
  Real p;
  flow Real m_flow;
end Base;
connector FluidPort
  extends Base;
  stream Real h_outflow;
end FluidPort;
model M
  FluidPort port;
equation
  port.p = 1;
  port.h_outflow = 2;
end M;
