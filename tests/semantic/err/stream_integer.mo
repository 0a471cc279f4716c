// expect: E2021 @5:10
connector FluidPort
  Real p;
  flow Real m_flow;
  stream Integer h;
end FluidPort;
