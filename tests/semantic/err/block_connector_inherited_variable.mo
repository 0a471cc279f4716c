// expect: E2027 @10:8
connector Base
  Real v;
end Base;
connector Port
  extends Base;
  input Real w;
end Port;
block B
  Port p;
  output Real y = 1;
end B;
