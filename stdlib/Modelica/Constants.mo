within Modelica;
package Constants "Library of mathematical constants and constants of nature (e.g., pi, eps, R, sigma)"
  import Modelica.Units.SI;

  // Mathematical constants
  // (MSL writes Modelica.Math.exp and Modelica.Math.asin; exp and asin are the
  // built-in functions of the same meaning)
  final constant Real e = exp(1.0);
  final constant Real pi = 2*asin(1.0); // 3.14159265358979;
  final constant Real D2R = pi/180 "Degree to Radian";
  final constant Real R2D = 180/pi "Radian to Degree";

  // Machine dependent constants
  // (MSL: = ModelicaServices.Machine.eps, .small, .inf, whose values are these literals)
  final constant Real eps = 1e-15 "Biggest number such that 1.0 + eps = 1.0";
  final constant Real small = 1e-60
    "Smallest number such that small and -small are representable on the machine";
  final constant Real inf = 1e60
    "Biggest Real number such that inf and -inf are representable on the machine";

  // Constants of nature
  final constant SI.Acceleration g_n = 9.80665
    "Standard acceleration of gravity on earth";
end Constants;
