within UnilateralMBS.Constraints;
partial model UnilateralConstraintAcausal "Unilateral constraint: kinematics, impact detection and impact impulses with dry friction"
  // The paper declares this class as `model`; it is `partial` here because State and the
  // closest-point geometry (rPA, rPB, lambda, mu, gradients) are defined only by derived
  // classes (UnilateralConstraintAcausalAddOnRegular, SurfacesOfConstraintAcausalDifferential
  // and a concrete pair of surfaces), so it is not locally balanced (MLS section 4.7).
  extends ConstraintImpacts;
  parameter Real k "Coefficient of restitution";
  parameter Real f "Coefficient of Coulomb friction";
  parameter SI.Velocity delta "Regularising parameter of dry friction";
  // added (not in the paper): without friction (f = 0) sliding and rolling have the same
  // dynamics (no tangential force), so the contact is then always Sliding. A frictionless
  // scene has no slide/roll switching: with f folded at compile time (the default), no
  // relation |v_rt| <= delta is left to watch and no Sliding/Rolling event happens.
  final parameter Boolean Friction = f > 0 "Whether the contact has Coulomb friction";
  Interfaces.UnilateralConstraintState State "0 = Flight, 1 = Sliding, 2 = Rolling";
  Boolean Impact "True at the instant of an impact";
  Boolean NormalImpact;
  Boolean NormalImpactIndicator;
  // start=true, fixed=true added: the mask is open at the start (the paper gives no start)
  Boolean ImpactMask(start=true, fixed=true) "Closed only after a smooth launch from the constraint";
  Real[3] normA "Unit outer normal of A at P_A, AF";
  SI.Impulse ImpactForcen "Normal component of the impulse on A";
  SI.Impulse[3] ImpactForcet "Tangent part of the impulse on A";
  SI.Impulse kappa "Auxiliary scalar of the tangent impulse equation";
  SI.Acceleration[3] arA "Rate of change of vrA (physical time)";
  SI.Acceleration[3] arB "Rate of change of vrB (physical time)";
  SI.Acceleration[3] rela "Relative acceleration arA - arB";
  SI.Acceleration relan "Normal component of rela";
  SI.Length muFlight "mu in Flight, 1 in contact";
  SI.Length muApproach "mu while the bodies approach in Flight, else 1 (added, not in the paper)";
  SI.Velocity relvnApproach "relvn in Flight with the impact mask open, else -1 (added, not in the paper)";
  SI.Velocity relvnFlight "relvn in Flight, 0 in contact";
  SI.Acceleration relanFlight "relan in Flight, 0 in contact";
  // printed in the paper (fixed=true added so that the initial value problem is complete)
  Real Active(start=1, fixed=true) "dt/dtau: scale of the independent variable";

  // reconstructed: declarations elided by the paper (intermediate variables of
  // formulae (2.1)-(2.4), (2.7) and the impact signal ports)
  SI.Position rPA[3] "Point P_A of A closest to B, AF";
  SI.Position rPB[3] "Point P_B of B closest to A, AF";
  Real lambda "Multiplier of (2.1): grad g_A = -lambda*grad g_B";
  Real mu "Multiplier of (2.1): r_PA - r_PB = mu*grad g_B (> 0 apart, 0 in contact)";
  Real gradgA[3] "grad g_A at P_A, AF (2.2)";
  Real gradgB[3] "grad g_B at P_B, AF (2.2)";
  SI.Velocity vrA[3](each stateSelect=StateSelect.avoid) "Velocity of the material point of A at P_A, AF";
  SI.Velocity vrB[3](each stateSelect=StateSelect.avoid) "Velocity of the material point of B at P_B, AF";
  SI.Velocity vrAt[3] "Tangent part of vrA";
  SI.Velocity vrBt[3] "Tangent part of vrB";
  SI.Velocity DeltavrA[3] "Impact increment of vrA (2.7)";
  SI.Velocity DeltavrB[3] "Impact increment of vrB (2.7)";
  SI.Velocity DeltavrAt[3] "Tangent part of DeltavrA";
  SI.Velocity DeltavrBt[3] "Tangent part of DeltavrB";
  SI.Velocity relv[3] "Relative velocity v_r = vrA - vrB (2.4)";
  SI.Velocity relvn(stateSelect=StateSelect.avoid) "Normal relative velocity v_rn (2.4)";
  SI.Velocity relvt[3] "Tangent relative velocity v_rt (2.4)";
  SI.Velocity relvtsqrt "|v_rt|";
  Modelica.Blocks.Interfaces.BooleanOutPort OutImpactSignalA "Impact signal to body A";
  Modelica.Blocks.Interfaces.BooleanOutPort OutImpactSignalB "Impact signal to body B";
  // added (not in the paper): enumerated view of State, for plotting and readability
  Interfaces.UnilateralConstraintStateName StateName = if State == 0 then Interfaces.UnilateralConstraintStateName.Flight
    elseif State == 1 then Interfaces.UnilateralConstraintStateName.Sliding
    else Interfaces.UnilateralConstraintStateName.Rolling "State as an enumeration";
algorithm
  // changed (not in the paper; S11): the mask also waits for the bodies to be apart or
  // separating (muApproach > 0). At a lift-off the contact leaves a penetration of the order of the
  // integration error (-5e-11 at rtol 1e-10) and relan read at the lift-off event is
  // not the free-flight value (1.59 instead of about 0 on FlySlideRoll at t = 14.70):
  // the mask reopened at once and an approach velocity of 3e-10 fired an impact that
  // landed the body in Rolling, where the reference lifts off.
  when relanFlight > 0 and muApproach > 0 and not ImpactMask then
    ImpactMask := true;
  end when;
  when State == 0 and pre(State) <> 0 then
    ImpactMask := false;
  end when;
equation
  // changed (not in the paper): an impact also needs the bodies to approach (relvn > 0
  // with relv = vrA - vrB and normA pointing from A to B). Without it, a penetration
  // mu < 0 of the drift's size while the bodies separate fires an "impact" that
  // reverses a separating velocity into an approaching one: a spurious Zeno sequence.
  // The tests of Flight read muFlight, relvnFlight and relanFlight (added, not in the
  // paper): equal to mu, relvn and relan in Flight and constant in contact, where those
  // hover at 0 and every rounding-level sign change would be a zero crossing (an event
  // that changes nothing, thousands per second of rolling).
  muFlight = if State == 0 then mu else 1;
  relvnFlight = if State == 0 then relvn else 0;
  relanFlight = if State == 0 then relan else 0;
  // changed (not in the paper; S11): also pre(State) == 0. At a lift-off event the
  // indicator was evaluated with State = 0 before the algorithm closed ImpactMask, so an
  // approach of the integration error's size (3e-10) fired an impact at the lift-off.
  // changed (not in the paper; S12): the penetration test reads muApproach, which is mu
  // only while the bodies approach. With closed-form closest points mu is a difference of
  // two O(1) numbers: right after an impact it sits at 0 within rounding while the
  // bodies separate at 1e-6 on a time scale of 1e-6, and every rounding flip of
  // `mu < 0` was an event (E4006 chattering after impacts of FlySlideRoll's Zeno tails).
  // relvnApproach (S12): relvn only while the mask is open. Right after a lift-off relvn
  // starts at 0 and grows like relan*t with relan about 0 too; its rounding (1e-14 for a
  // body spinning at 10 rad/s) flipped `relvn > 0` 200 times in a row (E4006 on
  // FlySlideRoll at t = 66.94, BDF rtol 1e-10). With the mask closed nothing reads it.
  relvnApproach = if ImpactMask then relvnFlight else -1;
  muApproach = if relvnApproach > 0 then muFlight else 1;
  NormalImpactIndicator = if muApproach < 0 and State == 0 and pre(State) == 0 and ImpactMask then true else false;
  NormalImpact = edge(NormalImpactIndicator);
  Impact = if noEvent(NormalImpact) then true else false;
  Active*arA = der(vrA);
  Active*arB = der(vrB);
  rela = arA - arB;
  relan = rela*normA;
  ImpactForcen = OutPortA.ImpactForce*normA;
  ImpactForcet = OutPortA.ImpactForce - ImpactForcen*normA;
  if noEvent(Impact) then
    if relvtsqrt <= delta then
      zeros(3) = ImpactForcet + f*abs(ImpactForcen)*relvt/delta - kappa*normA;
    else
      zeros(3) = ImpactForcet + f*abs(ImpactForcen)*relvt/relvtsqrt - kappa*normA;
    end if;
  else
    zeros(3) = DeltavrAt + vrAt - vrBt - DeltavrBt - kappa*normA;
  end if;
  der(Active) = 0;

  // reconstructed: equations elided by the paper
  // (a) impact signal transmission (the paper: "now under further development")
  OutImpactSignalA.signal[1] = Impact;
  OutImpactSignalB.signal[1] = Impact;
  // (b) intermediate variables of formulae (2.3), (2.4), (2.7)
  normA = gradgA/sqrt(gradgA*gradgA);
  vrA = InPortA.v + cross(InPortA.omega, rPA - InPortA.r);
  vrB = InPortB.v + cross(InPortB.omega, rPB - InPortB.r);
  vrAt = vrA - (vrA*normA)*normA;
  vrBt = vrB - (vrB*normA)*normA;
  relv = vrA - vrB;
  relvn = relv*normA;
  relvt = relv - relvn*normA;
  relvtsqrt = sqrt(relvt*relvt);
  DeltavrA = InPortA.Deltav + cross(InPortA.Deltaomega, rPA - InPortA.r);
  DeltavrB = InPortB.Deltav + cross(InPortB.Deltaomega, rPB - InPortB.r);
  DeltavrAt = DeltavrA - (DeltavrA*normA)*normA;
  DeltavrBt = DeltavrB - (DeltavrB*normA)*normA;
  // Newton's law for the normal impact (2.7): Deltav_rn = -(1 + k)*v_rn. Solved at all
  // times like the rest of the impact subsystem; its increments are applied only when
  // Impact is true.
  (DeltavrA - DeltavrB)*normA = -(1 + k)*relvn;
  // the wrenches act at the closest points
  OutPortA.P = rPA;
  OutPortB.P = rPB;
end UnilateralConstraintAcausal;
