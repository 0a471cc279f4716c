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
end ExpandableBus;
