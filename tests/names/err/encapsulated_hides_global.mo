model Helper
  Real y;
equation
  y = 1;
end Helper;

encapsulated model A
  Helper h;
end A;
