model A
  Integer n = 99999999999999999999;
end A;
