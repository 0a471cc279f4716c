// public and protected sections in models, blocks, packages and functions.
model Tank "Tank with protected internals"
public
  parameter Real A = 2 "Cross-section area";
  parameter Real k = 0.5 "Outflow coefficient";
  Real qIn = 0.3 "Inflow";
  Real level(start = 1, fixed = true) "Liquid level";
protected
  constant Real g = 9.81;
  parameter Real cv = k * sqrt(2 * g) "Valve constant";
  Real qOut "Outflow";
public
  Real volume "Public again after a protected section";
equation
  A * der(level) = qIn - qOut;
  qOut = cv * sqrt(max(level, 0));
  volume = A * level;
end Tank;

block Averager "Block with protected state"
  parameter Real T = 1 "Averaging time constant";
  input Real u;
  output Real y;
protected
  Real s(start = 0, fixed = true) "Internal filter state";
equation
  T * der(s) = u - s;
  y = s;
end Averager;

package Counters "Package with a protected helper"
  function clampedIncrement "Increments, limited to a maximum"
    input Integer n;
    input Integer nMax = 10;
    output Integer m;
  protected
    Integer candidate;
  algorithm
    candidate := next(n);
    m := if candidate > nMax then nMax else candidate;
  end clampedIncrement;
protected
  function next "Not accessible from outside the package"
    input Integer n;
    output Integer m;
  algorithm
    m := n + 1;
  end next;
end Counters;

model PublicProtectedDemo
  Tank tank(qIn = 0.2 + 0.1 * sin(time));
  Averager avg(u = tank.level);
  parameter Integer c = Counters.clampedIncrement(9);
end PublicProtectedDemo;
