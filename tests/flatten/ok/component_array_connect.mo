model ComponentArrayConnect "connect(r.p, a): the connectors of an array of components form a connector array (spec 9.1.3)"
  connector Pin
    Real v;
    flow Real i;
  end Pin;
  model Resistor
    Pin p;
    Pin n;
    parameter Real R = 1;
  equation
    p.i + n.i = 0;
    p.v - n.v = R*p.i;
  end Resistor;
  model Source
    Pin p;
    Pin n;
    parameter Real V = 1;
  equation
    p.i + n.i = 0;
    p.v - n.v = V;
  end Source;
  model Ground
    Pin p;
  equation
    p.v = 0;
  end Ground;
  model Bank "Three resistors between two pin arrays"
    Pin a[3];
    Pin b[3];
    Resistor r[3](each R = 2);
  equation
    connect(r.p, a);
    connect(r.n, b);
  end Bank;
  Bank bank;
  Source s[3](V = {1, 2, 3});
  Ground gnd;
equation
  connect(s.p, bank.a);
  connect(s.n, bank.b);
  for k in 1:3 loop
    connect(s[k].n, gnd.p);
  end for;
end ComponentArrayConnect;
