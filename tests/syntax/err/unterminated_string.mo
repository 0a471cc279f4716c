model A
  Real x "height of the ball;
equation
  x = 1;
end A;
