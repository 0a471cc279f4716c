// expect: E2027 @6:10
operator record Complex2
  Real re;
  Real im;
  encapsulated operator '+'
    Real x;
  end '+';
end Complex2;
