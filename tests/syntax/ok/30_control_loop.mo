// A realistic block diagram: a PI controller regulating a first-order
// plant, built from blocks with causal connectors and connect equations.
within;

package Blocks "Minimal signal block library"
  connector RealInput = input Real "Real input signal";
  connector RealOutput = output Real "Real output signal";

  partial block SISO "Single input, single output"
    RealInput u "Input";
    RealOutput y "Output";
  end SISO;

  block Step "Step signal"
    parameter Real height = 1;
    parameter Real offset = 0;
    parameter Real startTime = 0;
    RealOutput y;
  equation
    y = offset + (if time < startTime then 0 else height);
  end Step;

  block Feedback "Difference of two signals"
    RealInput u1 "Reference";
    RealInput u2 "Feedback";
    RealOutput y;
  equation
    y = u1 - u2;
  end Feedback;

  block PI "Proportional-integral controller"
    extends SISO;
    parameter Real k = 1 "Gain";
    parameter Real Ti(min = 1e-9) = 1 "Integral time";
    Real x(start = 0, fixed = true) "Integrator state";
  equation
    der(x) = u / Ti;
    y = k * (u + x);
  end PI;

  block FirstOrder "First-order plant"
    extends SISO;
    parameter Real k = 1;
    parameter Real T = 1;
  initial equation
    y = 0;
  equation
    T * der(y) = k * u - y;
  end FirstOrder;
end Blocks;

model ControlLoop "Closed loop with a step in the set point"
  Blocks.Step setPoint(height = 1, startTime = 0.5);
  Blocks.Feedback error;
  Blocks.PI controller(k = 2, Ti = 0.5);
  Blocks.FirstOrder plant(k = 1, T = 2);
equation
  connect(setPoint.y, error.u1);
  connect(plant.y, error.u2);
  connect(error.y, controller.u);
  connect(controller.y, plant.u);
  annotation(experiment(StartTime = 0, StopTime = 10, Tolerance = 1e-6, Interval = 0.01));
end ControlLoop;
