package Delays "delay(e, delayTime[, delayMax]) against closed forms (tests/delay.rs)"
  model Closed "x(t) by the method of steps: 1 - t on [0, 1], + (t - 1)^2/2 on [1, 2], - (t - 2)^3/6 on [2, 3]"
    Real x(start = 1, fixed = true);
  equation
    der(x) = -delay(x, 1);
    annotation(experiment(StopTime = 3));
  end Closed;

  model Sine "sin(t - 0.5) after t = 0.5, sin(0) before; no states"
    Real y = delay(sin(time), 0.5);
    annotation(experiment(StopTime = 3));
  end Sine;

  model SineWithState "the same with a state whose steps do not follow the sine"
    Real x(start = 0, fixed = true);
    Real y = delay(sin(time), 0.5);
  equation
    der(x) = 1 - x;
    annotation(experiment(StopTime = 3));
  end SineWithState;

  model Variable "a delay varying in [0.25, 0.75] with delayMax = 1"
    Real d = 0.5 + 0.25*sin(time);
    Real x(start = 0, fixed = true);
    Real y = delay(cos(2*time), d, 1);
  equation
    der(x) = y;
    annotation(experiment(StopTime = 5));
  end Variable;

  model Held "a delay time that leaves [0, delayMax] is held in it"
    Real y = delay(time, 2*sin(time), 1);
    annotation(experiment(StopTime = 8));
  end Held;

  model Short "a delay shorter than the steps the states would take"
    Real x(start = 0, fixed = true);
  equation
    der(x) = delay(sin(time), 0.1);
    annotation(experiment(StopTime = 10));
  end Short;

  model Jump "the step of u at t = 1 reaches y at t = 1.5"
    Real u = if time > 1 then 1 else 0;
    Real y = delay(u, 0.5);
    Real x(start = 0, fixed = true);
  equation
    der(x) = y;
    annotation(experiment(StopTime = 3));
  end Jump;
end Delays;
