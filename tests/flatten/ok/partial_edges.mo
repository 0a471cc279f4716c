model PartialEdges "Legal uses near the partial-instance and binding-cycle rules"
  partial model Source
    Real y;
  end Source;
  model One
    extends Source;
  equation
    y = 1;
  end One;
  model User
    replaceable Source s;
    outer Source env "an outer of a partial class refers to its inner";
    Real z = s.y + env.y;
  end User;
  inner One env;
  User u(redeclare One s);
  parameter Real a = 1;
  parameter Real b = a + 1;
  parameter Real c[2] = {b, a} "reads other parameters without a cycle";
end PartialEdges;
