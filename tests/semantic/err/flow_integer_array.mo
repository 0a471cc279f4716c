// expect: E2021 @4:8
connector Port
  Real v[2];
  flow Integer n[2];
end Port;
