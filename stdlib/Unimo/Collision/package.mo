within Unimo;
package Collision "Collision detection and contact forces between rigid bodies (paper B without its limits)"
  type ShapeType = enumeration(
    Sphere "radius = dims[1]",
    Box "edge lengths dims[1..3]",
    Capsule "radius dims[1], length of the axis segment dims[2] (axis: body y)",
    Cylinder "radius dims[1], length dims[2] (axis: body y)",
    Cone "base radius dims[1], height dims[2] (axis: body y)",
    Ellipsoid "semi-axes dims[1..3]",
    HalfSpace "the half-space z <= 0 of the body frame (a floor)");

  type DampingLaw = enumeration(
    Clipped "paper B: D*ddelta/dt, clipped so the contact never pulls",
    HuntCrossley "Hunt-Crossley, stated by a coefficient of restitution e",
    Flores "Flores et al., stated by a coefficient of restitution e");

  model CollisionWorld "The world all collision bodies of a model join (declare it inner)"
    parameter Real g[3] = {0, 0, -9.81} "Gravity, used by the bodies of this package";
    parameter Real K = 1e6 "Contact stiffness (N/m^n)";
    parameter Real n = 1.5 "Exponent of the penetration (Hertz: 1.5)";
    parameter DampingLaw law = DampingLaw.Clipped "How the normal damping is stated";
    parameter Real D = 0 "Damping constant for the clipped law (N.s/m)";
    parameter Real e = 1 "Coefficient of restitution (Hunt-Crossley, Flores and impulses)";
    parameter Real muStatic = 0 "Friction coefficient below vSwitch (paper B's mu_r)";
    parameter Real muSliding = 0 "Friction coefficient at or above vSwitch (mu_s)";
    parameter Real vSwitch = 1e-3 "Switching velocity of the friction law (m/s)";
    parameter Real fMax = 1e30 "Cap on the friction force (N)";
    parameter Boolean impulses = false "Impacts as Newton restitution impulses (exact momentum) instead of penalty forces";
    parameter Real margin = 1e-3 "Pairs closer than this are tracked by the narrowphase (m)";
    parameter Real contactTolerance = 1e-9 "Distance at which a pair counts as touching (m)";
    parameter Integer broadphase = 0 "0: automatic, 1: all pairs (for comparison), 2: sweep and prune";
    parameter Boolean sweep = true "Catch pairs that pass through each other within a step (off: paper B's ghosting)";
    Real gaps[2] = collisionGaps(margin, contactTolerance, broadphase, sweep)
      "Smallest gap of pairs not in contact; separation of pairs in contact (zero crossings)";
    Integer contactChanges(start = 0, fixed = true) "Events at which pairs touched or separated";
  equation
    when {gaps[1] < 0, gaps[2] < 0} then
      contactChanges = pre(contactChanges) + 1;
    end when;
  end CollisionWorld;

  model CollisionBody "A shape placed by its body; joins the world (no id needed)"
    outer CollisionWorld world;
    parameter ShapeType shape = ShapeType.Sphere;
    parameter Real dims[3] = {0.1, 0, 0} "Dimensions, see ShapeType";
    parameter Boolean dynamic = true "false for obstacles fixed to the ground";
    parameter Real K = world.K;
    parameter Real n = world.n;
    parameter DampingLaw law = world.law;
    parameter Real D = world.D;
    parameter Real e = world.e;
    parameter Real muStatic = world.muStatic;
    parameter Real muSliding = world.muSliding;
    parameter Real vSwitch = world.vSwitch;
    parameter Real fMax = world.fMax;
    parameter Boolean impulses = world.impulses;
    parameter Real m = 1 "Mass (for impulses)";
    parameter Real I[3] = {1, 1, 1} "Principal moments of inertia, body frame (for impulses)";
    parameter Integer group = 0 "Bodies of the same nonzero group do not collide";
    input Real r[3] "Position of the body origin";
    input Real R[3, 3] "Rotation matrix, body to world";
    input Real v[3] "Velocity of the body origin";
    input Real w[3] "Angular velocity, world coordinates";
    output Real F[3] "Contact force on the body, at its origin";
    output Real T[3] "Contact torque about the body origin";
  equation
    cat(1, F, T) = collisionBody(Integer(shape), dims, r, R, v, w, dynamic, K, n,
      Integer(law), D, e, muStatic, muSliding, vSwitch, fMax, impulses, m, I, group);
    // Drawn by `unimo animate` (docs/animation.md); a HalfSpace is the plane z = 0.
    annotation(__unimo_visual(shape = shape, size = dims, position = r, rotation = R, normal = {0, 0, 1}));
  end CollisionBody;

  model Ball "A free homogeneous sphere"
    outer CollisionWorld world;
    parameter Real radius = 0.05;
    parameter Real m = 1;
    parameter Real r0[3] = {0, 0, 1};
    parameter Real v0[3] = {0, 0, 0};
    parameter Real w0[3] = {0, 0, 0};
    parameter Boolean gravity = true;
    final parameter Real J = 2 / 5 * m * radius ^ 2;
    Real r[3](start = r0, each fixed = true);
    Real v[3](start = v0, each fixed = true);
    Real w[3](start = w0, each fixed = true);
    CollisionBody body(shape = ShapeType.Sphere, dims = {radius, 0, 0}, m = m, I = {J, J, J},
      r = r, R = identity(3), v = v, w = w);
  equation
    der(r) = v;
    m * der(v) = body.F + (if gravity then m * world.g else zeros(3));
    J * der(w) = body.T;
  end Ball;

  model RigidBody "A free rigid body with a shape; orientation as a rotation matrix"
    outer CollisionWorld world;
    parameter ShapeType shape = ShapeType.Box;
    parameter Real dims[3] = {0.1, 0.1, 0.1};
    parameter Real m = 1;
    parameter Real I[3] = {1, 1, 1} "Principal moments of inertia, body frame";
    parameter Real r0[3] = {0, 0, 1};
    parameter Real R0[3, 3] = identity(3);
    parameter Real v0[3] = {0, 0, 0};
    parameter Real w0[3] = {0, 0, 0};
    Real r[3](start = r0, each fixed = true);
    Real R[3, 3](start = R0, each fixed = true);
    Real v[3](start = v0, each fixed = true);
    Real w[3](start = w0, each fixed = true) "World coordinates";
    Real Iw[3, 3] "Inertia tensor, world coordinates";
    input Real f[3] "Other force on the body, at its origin (an equation or a modifier: f = zeros(3) for none)";
    input Real t[3] "Other torque on the body, about its origin (t = zeros(3) for none)";
    CollisionBody body(shape = shape, dims = dims, m = m, I = I, r = r, R = R, v = v, w = w);
  equation
    der(r) = v;
    m * der(v) = body.F + f + m * world.g;
    der(R) = skew(w) * R;
    Iw = R * diagonal(I) * transpose(R);
    // Euler's equations in world coordinates: d(Iw w)/dt = T.
    Iw * der(w) + cross(w, Iw * w) = body.T + t;
  end RigidBody;

  model TranslatingBody "A body with a shape that translates only (its orientation is fixed, as if guided)"
    outer CollisionWorld world;
    parameter ShapeType shape = ShapeType.Box;
    parameter Real dims[3] = {0.1, 0.1, 0.1};
    parameter Real m = 1;
    parameter Real r0[3] = {0, 0, 1};
    parameter Real R0[3, 3] = identity(3) "The fixed orientation";
    parameter Real v0[3] = {0, 0, 0};
    Real r[3](start = r0, each fixed = true);
    Real v[3](start = v0, each fixed = true);
    input Real f[3] "Other force on the body (f = zeros(3) for none)";
    CollisionBody body(shape = shape, dims = dims, m = m, I = {1e30, 1e30, 1e30}, r = r, R = R0,
      v = v, w = zeros(3));
  equation
    der(r) = v;
    m * der(v) = body.F + f + m * world.g;
  end TranslatingBody;

  model Obstacle "A shape fixed to the ground"
    parameter ShapeType shape = ShapeType.Box;
    parameter Real dims[3] = {0.1, 0.1, 0.1};
    parameter Real r0[3] = {0, 0, 0};
    parameter Real R0[3, 3] = identity(3);
    CollisionBody body(shape = shape, dims = dims, dynamic = false, r = r0, R = R0,
      v = zeros(3), w = zeros(3));
  end Obstacle;
end Collision;
