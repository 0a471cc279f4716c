// expect: E2021 @5:8
type Mode = enumeration(On, Off);
connector Port
  Real v;
  flow Mode m;
end Port;
