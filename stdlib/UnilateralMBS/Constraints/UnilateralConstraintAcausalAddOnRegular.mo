within UnilateralMBS.Constraints;
partial model UnilateralConstraintAcausalAddOnRegular "Unilateral constraint switching Flight/Sliding/Rolling in one object, with regularised friction and landing"
  // The paper declares this class as `model`; it is `partial` here because the closest-point
  // geometry is still left to derived classes (SurfacesOfConstraintAcausalDifferential and a
  // concrete pair of surfaces).
  extends UnilateralConstraintAcausal;
  parameter SI.Length ClearanceTolerance "Predicted jump height below which a contact lands instead of bouncing";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pulls v_rn back to 0 in contact";
  SI.Force nu "Auxiliary scalar of the tangent force equation";
  SI.Force Forcen "Normal component of the reaction on A";
  SI.Force[3] Forcet "Tangent part of the reaction on A";
  SI.Length Gap "Signed distance of the closest points along the normal (> 0 apart)";
  SI.Acceleration Drelvn "Rate of change of relvn (physical time), free in Flight, 0 in contact";
  Real StateIndicator "Real state variable inside the algebraic loop: <= 0.5 Flight, else contact";
  // fixed=true added so that the initial value problem is complete
  SI.Length Clearance(start=1, fixed=true) "Predicted height of the current jump";
  // added (not in the paper): the time regularisation predicts the time to the next
  // impact as 2*|relvn/relan|, which holds only while the bodies accelerate towards each
  // other (relan > 0). In Flight with relan < 0 and a shrunken time scale the bodies
  // drift apart and the next impact is not near: the container resets the time scale
  // to 1 on this signal (otherwise physical time crawls at the last impact's scale).
  // added (not in the paper; S12): relvn as the landing test reads it, watched only while
  // a landing is possible (Clearance < ClearanceTolerance), so that rounding flips of
  // relvn at 0 after a lift-off are no events
  SI.Velocity relvnLanding = if Clearance < ClearanceTolerance then relvnFlight else -1 "relvn when a landing is possible, else -1";
  Boolean Launching = State == 0 and relanFlight < 0 and Active < 1 "Flight, accelerating apart, with a shrunken time scale";
equation
  // changed (not in the paper): in contact the paper pulls only v_rn back to 0, so the
  // normal velocity at landing (about sqrt(2*relan*ClearanceTolerance)) leaves a gap or a
  // penetration of v_rn/ConstraintAttraction that never closes, and the velocity-level
  // constraint drifts in position over a long contact. The Gap term makes the pull
  // critically damped in position (Baumgarte with 2*omega = ConstraintAttraction):
  // d(Gap)/dt = -relvn, so relvn' = -CA*relvn + CA^2/4*Gap drives both to 0.
  Gap = mu*sqrt(gradgB*gradgB);
  der(relvn) = Active*(Drelvn + (if StateIndicator > 0.5 then -ConstraintAttraction*relvn + ConstraintAttraction^2/4*Gap else 0));
  Forcen = OutPortA.F*normA;
  Forcet = OutPortA.F - Forcen*normA;
  if StateIndicator <= 0.5 then
    State = 0;
    Forcen = 0;
    Forcet - nu*normA = zeros(3);
    // changed (not in the paper; S12): the printed first test `muFlight > 0 and
    // relanFlight < 0` (then 0) is left out: with relanFlight < 0 the branch below gives 0
    // as well, so the result is the same, and the relation on mu is not watched (with
    // closed-form points it flips on rounding right after an impact).
    if false then
      StateIndicator = 0;
    else
      if Clearance < ClearanceTolerance then
        if relanFlight < 0 or relvnLanding < 0 then
          // Case of launch; changed (not in the paper): also while the bodies separate
          // (relvn < 0), e.g. at the impact that made Clearance small: the landing then
          // waits for the next approach instead of landing with the rebound velocity.
          StateIndicator = 0;
        else
          // Case of landing
          if relvtsqrt > delta or not Friction then
            StateIndicator = 1;
          else
            StateIndicator = 2;
          end if;
        end if;
      else
        StateIndicator = 0;
      end if;
    end if;
  else
    Drelvn = 0;
    if Friction and relvtsqrt <= delta then
      State = 2;
      StateIndicator = if Forcen > 0 then 0 else 2;
      Forcet - f*Forcen*relvt/delta - nu*normA = zeros(3);
    else
      State = 1;
      StateIndicator = if Forcen > 0 then 0 else 1;
      // Without friction the contact is Sliding also at |v_rt| <= delta: no 0/0.
      Forcet - (if Friction then f*Forcen*relvt/relvtsqrt else zeros(3)) - nu*normA = zeros(3);
    end if;
  end if;
  der(Clearance) = 0;
  // The paper writes two separate when-equations that both reinit Clearance. Modelica 3
  // allows reinit of a variable in one when-equation only (its when/elsewhen branches), so
  // they are merged. Impact needs State = 0 while StateIndicator > 0.5 means State > 0, so
  // both conditions cannot hold in the same solution and the merge keeps the behaviour.
  // changed (not in the paper): the paper reinits Clearance to 0.5*relvn^2/|Drelvn| with
  // relvn read at the impact, i.e. before the impulse (reinit values are taken before
  // any reinit is applied, MLS 8.3.6): the height of the jump that just ended. The jump
  // that follows starts with k*relvn, so its height is k^2 times that. Without k^2 a body
  // lands one bounce late, and with k = 0 never (it stops on the surface in Flight with
  // the impact test still true, so no new impact edge comes, and sinks).
  when Impact then
    reinit(Clearance, 0.5*abs(k^2*relvn*relvn/Drelvn));
  elsewhen StateIndicator > 0.5 then
    reinit(Clearance, 1);
  end when;
  OutPortA.M = zeros(3);
  OutPortA.ImpactTorque = zeros(3);
end UnilateralConstraintAcausalAddOnRegular;
