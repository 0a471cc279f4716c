// Expandable connectors (spec 9.1.3) and a short operator record.
package Buses
  expandable connector ControlBus "Signals are added by the connections"
    extends SignalBus;
    Real speed "declared member";
  end ControlBus;

  expandable connector SignalBus
  end SignalBus;

  operator record Current = Complex(re(unit = "A"), im(unit = "A"));

  record Complex
    Real re;
    Real im;
  end Complex;
end Buses;
