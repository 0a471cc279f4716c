// Expressions: number literal forms, Boolean and String literals,
// if-then-elseif-else expressions, dotted references with subscripts,
// named and positional arguments, string concatenation.
record Coordinates
  Real x;
  Real y;
end Coordinates;

record Segment
  Coordinates pts[2];
end Segment;

function hypot "Length of the hypotenuse"
  input Real x;
  input Real y = 0;
  output Real h;
algorithm
  h := sqrt(x ^ 2 + y ^ 2);
end hypot;

model Expressions
  constant Real c1 = 1e-3;
  constant Real c2 = .5;
  constant Real c3 = 2.;
  constant Real c4 = 1E+10;
  constant Real c5 = 3.14159;
  constant Real c6 = 6.022e23;
  constant Real c7 = 1.5E-2;
  constant Real c8 = 0.0;
  constant Integer i1 = 42;
  constant Integer i2 = 0;
  constant Boolean t = true;
  constant Boolean f = false;
  parameter Segment seg = Segment(pts = {Coordinates(x = 0, y = 0), Coordinates(x = 3, y = 4)});
  parameter Boolean flag = true;
  parameter String msg = "Answer: " + String(i1) + "!";
  Real dx = seg.pts[2].x - seg.pts[1].x;
  Real dy = seg.pts[2].y - seg.pts[1].y;
  Real len1 = hypot(dx, dy);
  Real len2 = hypot(y = dy, x = dx);
  Real len3 = hypot(dx, y = dy);
  Real len4 = hypot(dx);
  Real sel;
  Real clipped;
  Integer category;
  Boolean b;
  Real nested;
equation
  sel = if flag then len1 else 0;
  clipped = if time < 0.5 then 0 elseif time < 1 then time - 0.5 else 0.5;
  category = if len1 > 10 then 3 elseif len1 > 1 then 2 else 1;
  b = not flag or (len1 > 1 and c1 < c2) or f and t;
  nested = (if b then 1 else 2) + (if time > c2 then (if time > c3 then c3 else c2) else c8) * c7;
end Expressions;
