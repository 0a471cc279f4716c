// expect: E2021 @5:8
type Count = Integer(min = 0);
connector Port
  Real v;
  flow Count n;
end Port;
