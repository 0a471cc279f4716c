// An expandable connector (a bus) in a block.
expandable connector Bus
end Bus;
block B
  Bus bus;
  output Real y = 1;
end B;
