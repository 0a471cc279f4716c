// An algebraic loop whose equations switch with a relation on one of its own
// unknowns: each mode is linear (one Newton step solves it, the relation frozen),
// so the plan marks the block "switched linear". With noEvent the branch could
// change inside Newton's iteration: that loop stays a general switched block.
model SwitchedLinearLoop
  Real x(start = 1, fixed = true);
  Real w(start = 1, fixed = true);
  Real y, z, u, v;
equation
  der(x) = -y;
  y + z = x;
  z = if y > 0 then 2 * y else 3 * y;
  der(w) = -u;
  u + v = w;
  v = noEvent(if u > 0 then 2 * u else 3 * u);
end SwitchedLinearLoop;
