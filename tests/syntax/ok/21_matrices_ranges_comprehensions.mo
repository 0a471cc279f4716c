// Matrix constructors with ';' and ',', concatenation, ranges with and
// without step (Integer, Real, descending), array comprehensions with one
// and several iterators, and reductions with iterators.
model MatricesRanges
  parameter Integer n = 4;
  parameter Real M[2, 2] = [1, 2; 3, 4];
  parameter Real Row[1, 3] = [1, 2, 3] "Row matrix";
  parameter Real Col[3, 1] = [1; 2; 3] "Column matrix";
  parameter Real Wide[2, 4] = [M, M] "Horizontal concatenation";
  parameter Real Tall[4, 2] = [M; M] "Vertical concatenation";
  parameter Real Aug[2, 3] = [M, [5; 6]];
  parameter Real Nested[2, 2] = {{1, 0}, {0, 1}} "Nested array constructor";
  parameter Integer r1[5] = 1:5;
  parameter Integer r2[4] = 1:2:7;
  parameter Integer r3[n] = n:-1:1 "Descending range";
  parameter Real r4[5] = 0.0:0.25:1.0 "Real range";
  parameter Real squares[n] = {i ^ 2 for i in 1:n};
  parameter Real table[n, 2] = {{i, 2 * i} for i in 1:n};
  parameter Real toeplitz[3, 3] = {i - j for i in 1:3, j in 1:3} "Several iterators";
  parameter Real odds[4] = {k for k in 1:2:7};
  parameter Real fromVector[3] = {2 * e for e in {1.5, 2.5, 3.5}};
  parameter Real total = sum(squares[i] for i in 1:n) "Reduction with an iterator";
  parameter Real largest = max(M[i, j] for i in 1:2, j in 1:2);
  parameter Real prod = product(i for i in 1:n);
  Real x[n](each start = 1, each fixed = true);
  Real y[2];
  Real sliceSum;
equation
  der(x) = -{i * x[i] for i in 1:n};
  y = M * x[1:2];
  sliceSum = sum(x[2:end]) + sum(Tall[:, 1]) + Wide[1, end] + Row[1, 2:3] * Col[1:2, 1];
end MatricesRanges;
