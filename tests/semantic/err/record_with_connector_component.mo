// expect: E2027 @7:7
connector Pin
  Real v;
  flow Real i;
end Pin;
record R
  Pin p;
end R;
