// expect: E2021 @4:8
connector Port
  Real v;
  flow Integer[3] n;
end Port;
