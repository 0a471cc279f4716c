// expect: E2021 @6:8
type Count = Integer;
type Items = Count;
connector Port
  Real v;
  flow Items n;
end Port;
