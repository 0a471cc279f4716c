// Every built-in operator and function of the subset.
model Builtins
  parameter Real A[3, 3] = [1, 2, 0; 0, 1, 0; 0, 0, 2];
  parameter Real u[3] = {1, 0, 0};
  parameter Real w[3] = {0, 1, 0};
  parameter Real n3[3] = cross(u, w) "Vector cross product";
  parameter Real At[3, 3] = transpose(A);
  parameter Real Z[2, 3] = zeros(2, 3);
  parameter Real O[2] = ones(2);
  parameter Real F[2, 2] = fill(3.0, 2, 2);
  parameter Real I3[3, 3] = identity(3);
  parameter Integer nr = size(A, 1);
  parameter Integer dims[2] = size(A);
  parameter Real s = sum(u) + sum(A);
  parameter Real p = product({1, 2, 3});
  parameter Real mx = max({0.1, 0.7, 0.3});
  parameter Real mn = min(A);
  parameter Real inv = asin(0.5) + acos(0.5) + atan(1) + atan2(1, 2);
  parameter Real rounding = floor(2.7) + ceil(2.2);
  parameter Integer ii = integer(3.7);
  parameter Integer im = mod(7, 3) + rem(-7, 3) + div(7, 2);
  parameter Real rm = mod(7.5, 2) + rem(7.5, 2) + div(7.5, 2);
  parameter String s1 = String(42);
  parameter String s2 = String(3.14159, significantDigits = 3);
  parameter String s3 = String(true) + String(2, minimumLength = 4, leftJustified = false);
  Real x(start = 0.5, fixed = true);
  Real trig = sin(x) + cos(x) + tan(x);
  Real hyp = sinh(x) + cosh(x) + tanh(x);
  Real ex = exp(x) + log(1 + x) + log10(10 + x) + sqrt(abs(x));
  Real sg = sign(x - 0.3);
  Real clamp = min(x, 0.2) + max(x, 0.1);
  Real root = noEvent(if x > 0 then sqrt(x) else 0);
  Real sm = smooth(1, if x > 0 then x ^ 2 else 0);
  Integer step = integer(2 * time);
  Real saw = mod(time, 1.0);
  discrete Integer k(start = 0, fixed = true);
  Boolean high;
  Boolean rising;
  Boolean changed;
  discrete Real tInit;
  discrete Real xEnd(start = 0, fixed = true);
equation
  der(x) = -x + sin(time);
  high = x > 0.6;
  rising = edge(high);
  changed = change(k);
  when sample(0, 0.25) then
    k = pre(k) + 1;
  end when;
  when initial() then
    tInit = time;
  end when;
  when terminal() then
    xEnd = x;
  end when;
  when x > 0.9 then
    reinit(x, 0.5);
  end when;
  assert(x < 10, "x too large: " + String(x));
end Builtins;
