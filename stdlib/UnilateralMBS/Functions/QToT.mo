within UnilateralMBS.Functions;
function QToT "Rotation matrix body frame -> AF from the attitude quaternion {q0, q1, q2, q3}"
  // reconstructed: not printed in the paper. Convention: x_AF = q*x_body*conj(q), consistent
  // with der(q) = 0.5*QMult(q, {0, omega_body}). The quadratic form is divided by q*q, so
  // the result is exactly orthogonal even when the integrated q drifts off unit norm.
  input Real q[4] "Attitude quaternion (need not be exactly normalised)";
  output Real T[3, 3] "Rotation matrix body frame -> AF";
algorithm
  T := {{q[1]^2 + q[2]^2 - q[3]^2 - q[4]^2, 2*(q[2]*q[3] - q[1]*q[4]), 2*(q[2]*q[4] + q[1]*q[3])},
        {2*(q[2]*q[3] + q[1]*q[4]), q[1]^2 - q[2]^2 + q[3]^2 - q[4]^2, 2*(q[3]*q[4] - q[1]*q[2])},
        {2*(q[2]*q[4] - q[1]*q[3]), 2*(q[3]*q[4] + q[1]*q[2]), q[1]^2 - q[2]^2 - q[3]^2 + q[4]^2}}
       /(q*q);
  annotation (Inline=true, smoothOrder=2);
end QToT;
