// An expandable connector declares more signals than the model uses: the unused ones
// are only potentially present (spec 9.1.3), so the model balances.
package ExpandableBus
  expandable connector Bus
    Real speed;
    Real unused "declared, never connected";
  end Bus;
  connector RealOutput = output Real;
  model Source
    RealOutput y = 2 * time;
  end Source;
  model Use
    Bus bus;
    Source s;
    Real z;
  equation
    connect(s.y, bus.speed);
    z = bus.speed + 1;
    annotation(experiment(StopTime = 1));
  end Use;
  model Sub "a component with its own bus, connected to the outer one"
    Bus bus;
    Real w;
  equation
    w = bus.speed * 2;
  end Sub;
  model Chain "buses connected to buses: `unused` is on all three, nobody sets or reads it"
    Bus bus;
    Source s;
    Sub a;
    Sub b;
  equation
    connect(s.y, bus.speed);
    connect(bus, a.bus);
    connect(a.bus, b.bus);
    annotation(experiment(StopTime = 1));
  end Chain;
end ExpandableBus;
