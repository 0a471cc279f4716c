// integer, floor and ceil generate events: their values are discrete-time.
model M
  Real x = 3 * time;
  Integer i;
  Integer j = integer(floor(x));
  Integer k = if x > 1 then 1 else 2;
equation
  i = integer(x);
end M;
