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
  SI.Acceleration Drelvn "Rate of change of relvn (physical time), free in Flight, 0 in contact";
  Real StateIndicator "Real state variable inside the algebraic loop: <= 0.5 Flight, else contact";
  // fixed=true added so that the initial value problem is complete
  SI.Length Clearance(start=1, fixed=true) "Predicted height of the current jump";
  // added (not in the paper): the time regularisation predicts the time to the next
  // impact as 2*|relvn/relan|, which holds only while the bodies accelerate towards each
  // other (relan > 0). In Flight with relan < 0 and a shrunken time scale the bodies
  // drift apart and the next impact is not near: the container resets the time scale
  // to 1 on this signal (otherwise physical time crawls at the last impact's scale).
  Boolean Launching = State == 0 and relan < 0 and Active < 1 "Flight, accelerating apart, with a shrunken time scale";
equation
  der(relvn) = Active*(Drelvn + (if StateIndicator > 0.5 then -ConstraintAttraction*relvn else 0));
  Forcen = OutPortA.F*normA;
  Forcet = OutPortA.F - Forcen*normA;
  if StateIndicator <= 0.5 then
    State = 0;
    Forcen = 0;
    Forcet - nu*normA = zeros(3);
    if mu > 0 and relan < 0 then
      StateIndicator = 0;
    else
      if Clearance < ClearanceTolerance then
        if relan < 0 then
          // Case of launch
          StateIndicator = 0;
        else
          // Case of landing
          if relvtsqrt > delta then
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
    if relvtsqrt <= delta then
      State = 2;
      StateIndicator = if Forcen > 0 then 0 else 2;
      Forcet - f*Forcen*relvt/delta - nu*normA = zeros(3);
    else
      State = 1;
      StateIndicator = if Forcen > 0 then 0 else 1;
      Forcet - f*Forcen*relvt/relvtsqrt - nu*normA = zeros(3);
    end if;
  end if;
  der(Clearance) = 0;
  // The paper writes two separate when-equations that both reinit Clearance. Modelica 3
  // allows reinit of a variable in one when-equation only (its when/elsewhen branches), so
  // they are merged. Impact needs State = 0 while StateIndicator > 0.5 means State > 0, so
  // both conditions cannot hold in the same solution and the merge keeps the behaviour.
  when Impact then
    reinit(Clearance, 0.5*abs(relvn*relvn/Drelvn));
  elsewhen StateIndicator > 0.5 then
    reinit(Clearance, 1);
  end when;
  OutPortA.M = zeros(3);
  OutPortA.ImpactTorque = zeros(3);
end UnilateralConstraintAcausalAddOnRegular;
