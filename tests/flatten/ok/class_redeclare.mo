package Sensors "replaceable classes and packages, redeclared three ways"
  partial model PartialSensor
    input Real x;
    output Real y;
  end PartialSensor;

  model IdealSensor
    extends PartialSensor;
  equation
    y = x;
  end IdealSensor;

  model OffsetSensor
    extends PartialSensor;
    parameter Real offset = 0.01;
  equation
    y = x + offset;
  end OffsetSensor;

  package PartialMedium
    constant Real cp = 1000;
  end PartialMedium;

  package Water
    extends PartialMedium(cp = 4184);
  end Water;

  model Plant
    replaceable model Sensor = IdealSensor constrainedby PartialSensor;
    replaceable package Medium = PartialMedium;
    Sensor sensor(x = T);
    Real T(start = 1, fixed = true);
    Real cp = Medium.cp;
  equation
    der(T) = -T;
  end Plant;

  model OffsetPlant "redeclared in an extends modifier"
    extends Plant(redeclare model Sensor = OffsetSensor(offset = 0.05));
  end OffsetPlant;

  model WaterPlant "redeclared as an element"
    extends Plant;
    redeclare package Medium = Water;
  end WaterPlant;
end Sensors;

model ClassRedeclare "class and package redeclarations"
  Sensors.Plant plain;
  Sensors.OffsetPlant offset;
  Sensors.WaterPlant water;
  Sensors.Plant both(redeclare model Sensor = Sensors.OffsetSensor(offset = 0.2),
    redeclare package Medium = Sensors.Water);
end ClassRedeclare;
