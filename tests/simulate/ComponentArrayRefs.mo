model ComponentArrayRefs "References through arrays of components (spec 10.6.9), String parameters compared at translation, array flows connected whole, an element assigned at a run-time index"
  connector HeatPort
    Real T;
    flow Real Q_flow;
  end HeatPort;
  connector Phasor "Array potential and flow variables"
    Real v[2];
    flow Real i[2];
  end Phasor;
  model Collector "m heat flows into one"
    parameter Integer m = 3;
    HeatPort port_a[m];
    HeatPort port_b;
  equation
    port_b.Q_flow + sum(port_a.Q_flow) = 0;
    port_a.T = fill(port_b.T, m);
  end Collector;
  model Source
    parameter Real Q = 1;
    HeatPort port;
  equation
    port.Q_flow = -Q;
  end Source;
  model Fixed
    parameter Real T = 300;
    HeatPort port;
  equation
    port.T = T;
  end Fixed;
  model PhasorSource
    Phasor p;
  equation
    p.v = {1, 2};
  end PhasorSource;
  model PhasorLoad
    Phasor p;
  equation
    p.i = 3 * p.v;
  end PhasorLoad;
  function substring "As Modelica.Utilities.Strings.substring (an external C function)"
    input String string;
    input Integer startIndex;
    input Integer endIndex;
    output String result;
  external "C" result = ModelicaStrings_substring(string, startIndex, endIndex);
  end substring;
  parameter String group = "Dy01";
  parameter String first = substring(group, 1, 1);
  parameter Real factor = if first == "D" then 2 else 3;
  Collector c;
  Source s[3](Q = {1, 2, 3});
  Fixed f;
  PhasorSource ps;
  PhasorLoad pl;
  Real total = f.port.Q_flow "The heat the fixed temperature takes: 6";
  Real temperatures = sum(s.port.T) "3 * 300";
  Real twoFlows = sum(s[2:3].port.Q_flow) "-2 - 3";
  Real scaled = factor * time "2 t: the group starts with D";
  Real sourceCurrent = ps.p.i[2] "-6";
  discrete Integer tick(start = 0, fixed = true);
  discrete Real buf[3](each start = 0, each fixed = true);
algorithm
  when sample(0.25, 0.25) then
    tick := pre(tick) + 1;
    if tick <= 3 then
      buf[tick] := 10 * tick + time;
    end if;
  end when;
equation
  connect(s.port, c.port_a);
  connect(c.port_b, f.port);
  connect(ps.p, pl.p);
end ComponentArrayRefs;
