// expect: E2021 @4:8
connector Port
  Real v;
  flow StateSelect s;
end Port;
