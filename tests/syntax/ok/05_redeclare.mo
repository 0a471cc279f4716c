// Replaceable classes and components, 'constrainedby', and 'redeclare'
// both in modifiers and as elements of a class body.
partial model PartialSensor "Interface of sensors"
  input Real x "Measured quantity";
  output Real y "Measurement";
end PartialSensor;

model IdealSensor "Perfect measurement"
  extends PartialSensor;
equation
  y = x;
end IdealSensor;

model OffsetSensor "Measurement with a constant offset"
  extends PartialSensor;
  parameter Real offset = 0.01;
equation
  y = x + offset;
end OffsetSensor;

package PartialMedium "Medium properties"
  constant Real cp = 1000 "Specific heat capacity";
end PartialMedium;

package Water "Water as medium"
  extends PartialMedium(cp = 4184);
end Water;

model Plant "Plant with replaceable parts"
  replaceable model Sensor = IdealSensor constrainedby PartialSensor(x(nominal = 1))
    "Sensor model" annotation(choicesAllMatching = true);
  replaceable package Medium = PartialMedium;
  replaceable IdealSensor extra(x = 0) constrainedby PartialSensor "Extra sensor";
  Sensor sensor(x = x);
  Real x(start = 1, fixed = true);
  Real energy = Medium.cp * x;
equation
  der(x) = -x;
end Plant;

model OffsetPlant "Class redeclared through an extends modifier"
  extends Plant(redeclare model Sensor = OffsetSensor(offset = 0.05));
end OffsetPlant;

model WaterPlant "Element redeclarations in the class body"
  extends Plant;
  redeclare replaceable package Medium = Water;
  redeclare OffsetSensor extra(x = 2 * x, offset = 0.1);
end WaterPlant;

model System "Redeclarations in component modifiers"
  Plant p1;
  OffsetPlant p2;
  WaterPlant p3;
  Plant p4(redeclare model Sensor = OffsetSensor, redeclare package Medium = Water);
  Plant p5(redeclare replaceable model Sensor = IdealSensor constrainedby PartialSensor);
  Plant p6(redeclare OffsetSensor extra(x = 1, offset = 0.2));
end System;
