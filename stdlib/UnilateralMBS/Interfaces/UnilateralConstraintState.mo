within UnilateralMBS.Interfaces;
// The paper declares `UnilateralConstraintState State;`, writes `State = 0`, `State == 0`,
// `pre(State) <> 0`, and says in the text that State "has the Integer type". So the type
// is an Integer subtype here; UnilateralConstraintStateName is the enumerated view.
type UnilateralConstraintState = Integer (min=0, max=2) "State of a unilateral constraint: 0 = Flight, 1 = Sliding, 2 = Rolling";
