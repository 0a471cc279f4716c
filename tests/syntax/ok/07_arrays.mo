// Array declarations with dimensions on the type or on the name,
// array equations, subscripts, slices, 'end' and index vectors.
record Point "Point in the plane"
  Real x;
  Real y;
end Point;

model ArrayDeclarations
  parameter Integer n = 4 "Number of states";
  parameter Real a[3] = {1.0, 2.0, 3.0};
  parameter Real[2, 3] B = {{1, 2, 3}, {4, 5, 6}};
  parameter Real[2] C[3] = {{1, 2}, {3, 4}, {5, 6}} "Dimensions on type and name: 3x2";
  Real x[n](each start = 0, each fixed = true);
  Real[3, 3] T "Rotation matrix";
  Real v[3];
  Real row[3];
  Real col[2];
  Real tail[n - 1];
  Real last;
  Real sel[2];
  Real sub[2, 2];
  Real corner;
equation
  for i in 1:n loop
    der(x[i]) = -i * x[i] + 1;
  end for;
  T = [cos(time), -sin(time), 0; sin(time), cos(time), 0; 0, 0, 1];
  v = T * a;
  row = B[2, :];
  col = B[:, 1];
  tail = x[2:end];
  last = x[end];
  sel = a[{1, 3}];
  sub = C[2:3, :];
  corner = T[end, end - 2] + B[1, 1:2] * C[1, :];
end ArrayDeclarations;

model RecordArrays "Arrays of records and dotted references"
  parameter Integer np = 3;
  parameter Point p[np] = {Point(x = 0, y = 0), Point(x = 1, y = 0), Point(x = 0, y = 1)};
  Point q[2](each x = 1, y = {2, 3});
  Real xs[np] = {p[i].x for i in 1:np};
  Real perimeter;
  Real qy;
equation
  perimeter = sum(sqrt((p[mod(i, np) + 1].x - p[i].x) ^ 2 + (p[mod(i, np) + 1].y - p[i].y) ^ 2) for i in 1:np);
  qy = q[2].y - q[1].y;
end RecordArrays;

model UnsizedDimensions "Unsized dimension fixed by the binding"
  parameter Real w[:] = {0.1, 0.2, 0.7};
  parameter Integer m = size(w, 1);
  Real y[m];
equation
  y = w * time;
end UnsizedDimensions;
