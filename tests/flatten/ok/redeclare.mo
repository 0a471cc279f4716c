package Sensors
  partial model Sensor
    input Real u;
    output Real y;
  end Sensor;
  model Ideal
    extends Sensor;
  equation
    y = u;
  end Ideal;
  model Offset
    extends Sensor;
    parameter Real off = 0.5;
  equation
    y = u + off;
  end Offset;
end Sensors;

model Plant
  replaceable Sensors.Ideal sensor constrainedby Sensors.Sensor;
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  sensor.u = x;
end Plant;

model Redeclare
  extends Plant(redeclare Sensors.Offset sensor(off = 2));
end Redeclare;
