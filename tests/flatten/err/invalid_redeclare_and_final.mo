model InvalidRedeclareAndFinal
  model A
    Real x = 1;
  end A;
  model B
    Real x = 2;
    Real y = 3;
  end B;
  model C "lacks x"
    Real z = 4;
  end C;
  model P
    model S = A;
    A a;
    final parameter Real k = 1;
    replaceable model S2 = A constrainedby A;
    replaceable A a2;
    S2 s2;
  end P;
  P p1(redeclare model S = B);
  P p2(redeclare B a);
  P p3(k = 2);
  P p4(redeclare model S2 = C);
  P p5(redeclare C a2);
  P p6(redeclare model S2 = B, redeclare B a2) "fine";
end InvalidRedeclareAndFinal;
