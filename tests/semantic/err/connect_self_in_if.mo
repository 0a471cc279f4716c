// expect: E2031 @11:5
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  parameter Boolean b = true;
  Pin p;
equation
  if b then
    connect(p, p);
  end if;
end M;
