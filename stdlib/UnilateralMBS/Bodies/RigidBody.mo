within UnilateralMBS.Bodies;
partial model RigidBody "Rigid body: translation and rotation, quaternion attitude, body-frame angular velocity, scaled independent variable"
  // Printed in the paper (section 3.2): the port declaration, Active and the five
  // der() equations. The paper elides the rest with dots ("parts of the RigidBody class
  // from the previous version which haven't been reconstructed"); those parts are
  // reconstructed from spec A.2 and marked "reconstructed".
  replaceable output Interfaces.KinematicPort OutPort "Kinematics of the body (output to constraints)";

  // reconstructed: parameters and variables elided by the paper
  parameter SI.Mass m = 1 "Mass";
  parameter SI.Inertia I[3, 3] = identity(3) "Central inertia tensor, body frame (principal axes)";
  SI.Position r[3](each fixed=true) "Centre of mass position, AF (initial value via start)";
  SI.Velocity v[3](each fixed=true) "Centre of mass velocity, AF (initial value via start)";
  SI.Acceleration a[3] "Centre of mass acceleration, AF (physical time)";
  Real q[4](start={1, 0, 0, 0}, each fixed=true) "Attitude quaternion body frame -> AF";
  Real T[3, 3] "Rotation matrix body frame -> AF";
  SI.AngularVelocity omega[3](each fixed=true) "Angular velocity, body frame (initial value via start)";
  SI.AngularAcceleration epsilon[3] "Angular acceleration, body frame (physical time)";
  SI.Force F[3] "Total force, AF (defined by derived classes)";
  SI.Torque M[3] "Total torque about the centre of mass, AF (defined by derived classes)";

  // printed in the paper (fixed=true added so that the initial value problem is complete)
  Real Active(start=1, fixed=true) "dt/dtau: scale of the independent variable (0 freezes the body)";
equation
  der(Active) = 0;
  der(r) = Active*v;
  der(v) = Active*a; // OCR garbled this line; restored from the pattern of the others and spec A.2
  der(q) = Active*0.5*Functions.QMult(q, {0, omega[1], omega[2], omega[3]});
  der(omega) = Active*epsilon;

  // reconstructed: dynamics (spec A.2) in physical time
  m*a = F;
  I*epsilon + cross(omega, I*omega) = transpose(T)*M;
  T = Functions.QToT(q);

  // reconstructed: kinematic port, all quantities resolved in AF
  OutPort.r = r;
  OutPort.T = T;
  OutPort.v = v;
  OutPort.omega = T*omega;
  OutPort.a = a;
  OutPort.epsilon = T*epsilon;
end RigidBody;
