// expect: E2027 @10:7
connector Pin
  Real v;
  flow Real i;
end Pin;
function f
  input Real u;
  output Real y = u;
protected
  Pin p;
end f;
