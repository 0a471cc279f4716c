package P
  model A
  end A;
  model A
  end A;
end P;
