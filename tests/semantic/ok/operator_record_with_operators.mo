// An operator record with an operator holding functions.
operator record Complex2
  Real re;
  Real im;
  operator '+'
    function add
      input Complex2 a;
      input Complex2 b;
      output Complex2 c;
    algorithm
      c := Complex2(a.re + b.re, a.im + b.im);
    end add;
  end '+';
end Complex2;
