model UnknownLaw "A direct collisionBody call with a damping law code that does not exist"
  Real F[6];
  Real r[3](each start = 1, each fixed = true);
equation
  der(r) = zeros(3);
  F = collisionBody(1, {0.1, 0, 0}, r, {1, 0, 0, 0, 1, 0, 0, 0, 1}, zeros(3), zeros(3), 1, 1e5, 1, 7, 0, 0.5, 0, 0, 1e-3, 1e9, 0, 1, {1, 1, 1}, 0);
end UnknownLaw;
