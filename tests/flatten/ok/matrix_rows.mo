// Matrix construction in equations (spec 10.4.2): each element is promoted to a
// matrix, so [y] of a 3-vector and [u1; u2; u3] of scalars are both 3 x 1, and [v; w]
// of 2-vectors is 4 x 1 (as Modelica.Blocks.Routing.Multiplex3 writes it); the balance
// counts their scalars, not their rows.
model MatrixRows
  Real u1 = 1;
  Real u2 = 2;
  Real u3 = 3;
  Real v[2] = {4, 5};
  Real w[2] = {6, 7};
  Real y[3];
  Real z[4];
  Real m[2, 3];
equation
  [y] = [u1; u2; u3];
  [z] = [v; w];
  m = [u1, u2, u3; v[1], v[2], w[1]];
end MatrixRows;
