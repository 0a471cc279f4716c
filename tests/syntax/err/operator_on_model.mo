package P
  operator model M
  end M;
  pure record R
    Real x;
  end R;
end P;
