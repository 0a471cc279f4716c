// expect: E2021 @4:8
connector Port "spec 9.3: a flow variable is a Real"
  Real v;
  flow Integer n;
end Port;
