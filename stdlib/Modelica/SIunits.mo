within Modelica;
package SIunits
  "Library of type and unit definitions based on SI units according to ISO 31-1992 (MSL 3.2.3 Modelica.SIunits, subset)"
  // Space and Time (chapter 1 of ISO 31-1992)
  type Angle = Real (
      final quantity="Angle",
      final unit="rad",
      displayUnit="deg");
  type Length = Real (final quantity="Length", final unit="m");
  type Position = Length;
  type Distance = Length (min=0);
  type Height = Length (min=0);
  type Area = Real (final quantity="Area", final unit="m2");
  type Volume = Real (final quantity="Volume", final unit="m3");
  type Time = Real (final quantity="Time", final unit="s");
  type AngularVelocity = Real (
      final quantity="AngularVelocity",
      final unit="rad/s");
  type AngularAcceleration = Real (final quantity="AngularAcceleration", final unit="rad/s2");
  type Velocity = Real (final quantity="Velocity", final unit="m/s");
  type Acceleration = Real (final quantity="Acceleration", final unit="m/s2");

  // Periodic and related phenomena (chapter 2 of ISO 31-1992)
  type Period = Real (final quantity="Time", final unit="s");
  type Frequency = Real (final quantity="Frequency", final unit="Hz");
  type DampingCoefficient = Real (final quantity="DampingCoefficient", final unit="s-1");

  // Mechanics (chapter 3 of ISO 31-1992)
  type Mass = Real (
      quantity="Mass",
      final unit="kg",
      min=0);
  type Density = Real (
      final quantity="Density",
      final unit="kg/m3",
      displayUnit="g/cm3",
      min=0.0);
  type Impulse = Real (final quantity="Impulse", final unit="N.s");
  type AngularImpulse = Real (final quantity="AngularImpulse", final unit="N.m.s");
  type MomentOfInertia = Real (final quantity="MomentOfInertia", final unit="kg.m2");
  type Inertia = MomentOfInertia;
  type Force = Real (final quantity="Force", final unit="N");
  type TranslationalSpringConstant = Real (final quantity="TranslationalSpringConstant", final unit="N/m");
  type TranslationalDampingConstant = Real (final quantity="TranslationalDampingConstant", final unit="N.s/m");
  type Torque = Real (final quantity="Torque", final unit="N.m");
  type RotationalSpringConstant = Real (final quantity="RotationalSpringConstant", final unit="N.m/rad");
  type Pressure = Real (
      final quantity="Pressure",
      final unit="Pa",
      displayUnit="bar");
  type Energy = Real (final quantity="Energy", final unit="J");
  type Power = Real (final quantity="Power", final unit="W");

  // Heat (chapter 4 of ISO 31-1992)
  type ThermodynamicTemperature = Real (
      final quantity="ThermodynamicTemperature",
      final unit="K",
      min=0.0,
      start=288.15,
      nominal=300,
      displayUnit="degC")
    "Absolute temperature (use type TemperatureDifference for relative temperatures)"
    annotation (absoluteValue=true);
  type Temperature = ThermodynamicTemperature;

  // Electricity and Magnetism (chapter 5 of ISO 31-1992)
  type ElectricCurrent = Real (final quantity="ElectricCurrent", final unit="A");
  type Current = ElectricCurrent;
  type ElectricCharge = Real (final quantity="ElectricCharge", final unit="C");
  type Charge = ElectricCharge;
  type ElectricPotential = Real (final quantity="ElectricPotential", final unit="V");
  type Voltage = ElectricPotential;
  type Capacitance = Real (
      final quantity="Capacitance",
      final unit="F",
      min=0);
  type Inductance = Real (
      final quantity="Inductance",
      final unit="H");
  type Resistance = Real (
      final quantity="Resistance",
      final unit="Ohm");
end SIunits;
