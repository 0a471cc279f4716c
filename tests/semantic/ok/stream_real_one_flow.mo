// A stream connector: one flow variable and a Real stream variable.
connector FluidPort
  Real p;
  flow Real m_flow;
  stream Real h_outflow;
end FluidPort;
