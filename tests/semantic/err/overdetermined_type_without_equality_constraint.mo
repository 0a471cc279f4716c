// expect: E2036 @14:29
// A record used as overdetermined without an equalityConstraint function.
record Orientation
  Real T[3, 3];
end Orientation;
connector Frame
  Real r[3];
  Orientation R;
  flow Real f[3];
end Frame;
model M
  Frame frame;
equation
  Connections.potentialRoot(frame.R);
end M;
