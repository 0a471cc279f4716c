// x is given both by its derivative and as a function of time: after index reduction
// two equations determine der(x), and nothing determines y or z.
model OverDetermined
  Real x, y, z;
equation
  der(x) = 1;
  x = time;
  y + z = 1;
end OverDetermined;
