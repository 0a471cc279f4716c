// expect: E2009 @6:6
partial block SO
  output Real y;
end SO;
model M
  SO b;
end M;
