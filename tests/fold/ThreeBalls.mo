package ThreeBalls "models/ThreeBallsOnTable.mo with and without friction (tests/fold.rs)"
  model WithFriction "ball-table friction 0.1 (ball-ball contacts are frictionless in the model)"
    extends ThreeBallsOnTable(fTable = 0.1);
  end WithFriction;
  model Frictionless "no friction anywhere"
    extends ThreeBallsOnTable(fTable = 0, fBalls = 0);
  end Frictionless;
end ThreeBalls;
