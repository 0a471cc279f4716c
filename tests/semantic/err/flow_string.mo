// expect: E2021 @4:8
connector Port
  Real v;
  flow String s;
end Port;
