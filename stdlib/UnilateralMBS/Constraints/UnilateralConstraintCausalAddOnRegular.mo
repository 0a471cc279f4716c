within UnilateralMBS.Constraints;
partial model UnilateralConstraintCausalAddOnRegular "Causal reference: the state Flight/Sliding/Rolling is a discrete Integer switched only in when-clauses (hybrid automaton), same equations per state as UnilateralConstraintAcausalAddOnRegular (added; not in the paper)"
  // added (not in the paper): the reference model of paper A's comparison ("causal").
  // UnilateralConstraintAcausalAddOnRegular decides the state with the Real StateIndicator
  // inside the algebraic loop. Here State (declared in UnilateralConstraintCausal) is a
  // discrete Integer assigned only in when-statements whose guards read pre(State), so
  // the state is never an unknown of the continuous system. Per state the equations are
  // those of the acausal object: the same regularised friction, the same Baumgarte term
  // with the Gap, the same Clearance (with k^2) and the same flight-only test signals.
  // Base class: UnilateralConstraintCausal (UnilateralConstraintAcausal where a landing
  // has priority over an impact at the same instant). The guards restate the acausal
  // decision tree:
  //   Flight -> contact (landing): Clearance < ClearanceTolerance and not (relan < 0 or
  //     relvn < 0), i.e. the acausal "Case of landing"; the contact is Sliding if
  //     |v_rt| > delta, else Rolling. Otherwise the flight ends by an impact (impact law
  //     of UnilateralConstraintAcausal, unchanged).
  //   contact -> Flight (lift-off): Forcen > 0.
  //   Sliding -> Rolling: |v_rt| <= delta;  Rolling -> Sliding: |v_rt| > delta.
  // The initial state is a parameter: unimo does not (yet) solve a discrete variable in
  // the initial system (an initial equation for State, or `when initial()` in the
  // algorithm, fails), see /work/notes/causal-helper.md. The container computes it from
  // the initial data like the acausal landing test would.
  extends UnilateralConstraintCausal(State(start=State0, fixed=true));
  parameter Integer State0 = 0 "Initial state: 0 = Flight, 1 = Sliding, 2 = Rolling";
  parameter SI.Length ClearanceTolerance "Predicted jump height below which a contact lands instead of bouncing";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pulls v_rn back to 0 in contact";
  SI.Force nu "Auxiliary scalar of the tangent force equation";
  SI.Force Forcen "Normal component of the reaction on A";
  SI.Force[3] Forcet "Tangent part of the reaction on A";
  SI.Length Gap "Signed distance of the closest points along the normal (> 0 apart)";
  SI.Acceleration Drelvn "Rate of change of relvn (physical time), free in Flight, 0 in contact";
  Real NormalUnknown "Drelvn in Flight, Forcen in contact";
  SI.Length Clearance(start=1, fixed=true) "Predicted height of the current jump";
  Boolean Launching = State == 0 and relanFlight < 0 and Active < 1 "Flight, accelerating apart, with a shrunken time scale";
  // guards of the automaton; they read pre(State) so that State never sits in a loop
  SI.Velocity relvnGuard "relvn while the previous state is Flight, 0 otherwise";
  SI.Acceleration relanGuard "relan while the previous state is Flight, 0 otherwise";
  SI.Force ForcenGuard "Forcen while the previous state is a contact, 0 otherwise";
  Boolean LiftOff "Sliding/Rolling -> Flight";
  Boolean ToRolling "Sliding -> Rolling";
  Boolean ToSliding "Rolling -> Sliding";
equation
  relvnGuard = if pre(State) == 0 then relvn else 0;
  relanGuard = if pre(State) == 0 then relan else 0;
  ForcenGuard = if pre(State) > 0 then Forcen else 0;
  Landing = pre(State) == 0 and Clearance < ClearanceTolerance and not (relanGuard < 0 or relvnGuard < 0);
  LiftOff = pre(State) > 0 and ForcenGuard > 0;
  ToRolling = Friction and pre(State) == 1 and relvtsqrt <= delta;
  ToSliding = pre(State) == 2 and relvtsqrt > delta;

  // same as the acausal object, StateIndicator > 0.5 read as State > 0
  Gap = mu*sqrt(gradgB*gradgB);
  der(relvn) = Active*(Drelvn + (if State > 0 then -ConstraintAttraction*relvn + ConstraintAttraction^2/4*Gap else 0));
  Forcen = OutPortA.F*normA;
  Forcet = OutPortA.F - Forcen*normA;
  // Flight: Forcen = 0, Drelvn free; contact: Drelvn = 0, Forcen free. Written as two
  // equations in which every unknown has the coefficient +-1 in every state, with the
  // auxiliary unknown NormalUnknown (= Drelvn in Flight, Forcen in contact): unimo solves
  // `if State == 0 then Forcen = 0; else Drelvn = 0; end if;` (or
  // `Forcen = if State == 0 then 0 else NormalUnknown`) symbolically for a variable whose
  // coefficient is 0 in one state and divides by it, see /work/notes/causal-helper.md.
  Forcen + Drelvn = NormalUnknown;
  Forcen - Drelvn = if State == 0 then -NormalUnknown else NormalUnknown;
  if State == 0 then
    Forcet - nu*normA = zeros(3);
  elseif State == 2 then
    Forcet - f*Forcen*relvt/delta - nu*normA = zeros(3);
  else
    // Without friction the contact is Sliding also at |v_rt| <= delta: no 0/0.
    Forcet - (if Friction then f*Forcen*relvt/relvtsqrt else zeros(3)) - nu*normA = zeros(3);
  end if;
  der(Clearance) = 0;
  when Impact then
    reinit(Clearance, 0.5*abs(k^2*relvn*relvn/Drelvn));
  elsewhen State > 0 then
    reinit(Clearance, 1);
  end when;
  OutPortA.M = zeros(3);
  OutPortA.ImpactTorque = zeros(3);
algorithm
  when Landing then
    State := if relvtsqrt > delta or not Friction then 1 else 2;
  elsewhen LiftOff then
    State := 0;
  elsewhen ToRolling then
    State := 2;
  elsewhen ToSliding then
    State := 1;
  end when;
end UnilateralConstraintCausalAddOnRegular;
