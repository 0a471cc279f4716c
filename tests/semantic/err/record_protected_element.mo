// expect: E2027 @5:8
record R
  Real x;
protected
  Real y;
end R;
