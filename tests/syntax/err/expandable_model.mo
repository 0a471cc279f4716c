// `expandable` refines only connectors.
expandable model Bus
  Real x;
equation
  x = 1;
end Bus;
