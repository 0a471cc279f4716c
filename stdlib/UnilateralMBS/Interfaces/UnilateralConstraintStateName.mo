within UnilateralMBS.Interfaces;
type UnilateralConstraintStateName = enumeration(
    Flight "State = 0: bodies apart, no reaction",
    Sliding "State = 1: contact with relative slipping",
    Rolling "State = 2: contact without relative slipping") "Enumerated names of the constraint states (added; not in the paper)";
