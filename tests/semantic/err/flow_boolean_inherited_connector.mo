// expect: E2021 @7:8
connector Base
  Real v;
end Base;
connector Port
  extends Base;
  flow Boolean b;
end Port;
