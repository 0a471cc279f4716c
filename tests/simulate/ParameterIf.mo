// An if-expression whose condition is a parameter takes its branch at compile time
// (as Modelica.Blocks.Interfaces.Adaptors.FlowToPotentialAdaptor's
// `y1 = if use_pder then der(y) else 0` with use_pder = false): the der(y) of the
// branch not taken never reaches the structure, so y stays an algebraic variable
// computed from the input and needs no derivative.
model ParameterIf
  parameter Boolean use_pder = false;
  Real u = sin(time);
  Real y;
  Real y1;
equation
  y = u;
  y1 = if use_pder then der(y) else 0;
end ParameterIf;
