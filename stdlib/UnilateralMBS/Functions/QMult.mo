within UnilateralMBS.Functions;
function QMult "Quaternion (Hamilton) product p*q, quaternions stored as {scalar, x, y, z}"
  // reconstructed: used by RigidBody (der(q) = Active*0.5*QMult(q, {0, omega})) but not
  // printed in the paper.
  input Real p[4] "Left factor";
  input Real q[4] "Right factor";
  output Real pq[4] "Product p*q";
algorithm
  pq := {p[1]*q[1] - p[2]*q[2] - p[3]*q[3] - p[4]*q[4],
         p[1]*q[2] + p[2]*q[1] + p[3]*q[4] - p[4]*q[3],
         p[1]*q[3] - p[2]*q[4] + p[3]*q[1] + p[4]*q[2],
         p[1]*q[4] + p[2]*q[3] - p[3]*q[2] + p[4]*q[1]};
  annotation (Inline=true, smoothOrder=2);
end QMult;
