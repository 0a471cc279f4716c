model ConnectSubconnectorOutside "connect(r.port, internal.heat): an element of a connector the class declares is an outside connector (spec 9.1.2), like the connector itself"
  connector HeatPort
    Real T;
    flow Real Q_flow;
  end HeatPort;
  connector ThermalPort "A connector of connectors"
    HeatPort heat[2];
  end ThermalPort;
  model Source "Gives off a fixed heat flow at its port's temperature"
    parameter Real Q = 1;
    HeatPort port;
  equation
    port.Q_flow = -Q;
  end Source;
  model Fixed "A fixed temperature"
    parameter Real T = 300;
    HeatPort port;
  equation
    port.T = T;
  end Fixed;
  model Ambient "Fixed temperatures at a thermal port"
    ThermalPort thermal;
    Fixed fixed[2](T = {300, 310});
  equation
    for k in 1:2 loop
      connect(fixed[k].port, thermal.heat[k]);
    end for;
  end Ambient;
  model Device "Two sources wired to an internal thermal port"
    Source s[2](Q = {1, 2});
    Ambient ambient;
  protected
    ThermalPort internal;
  equation
    connect(ambient.thermal, internal);
    connect(s[1].port, internal.heat[1]);
    connect(s[2].port, internal.heat[2]);
  end Device;
  Device d;
  Real q2 = d.ambient.fixed[2].port.Q_flow "The heat the second fixed temperature takes: 2";
end ConnectSubconnectorOutside;
