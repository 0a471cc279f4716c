model InvalidRedeclareAndFinal
  model A
    Real x = 1;
  end A;
  model B
    Real x = 2;
    Real y = 3;
  end B;
  model P
    model S = A;
    A a;
    final parameter Real k = 1;
  end P;
  P p1(redeclare model S = B);
  P p2(redeclare B a);
  P p3(k = 2);
end InvalidRedeclareAndFinal;
