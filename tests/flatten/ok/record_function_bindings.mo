package RecordFunctionLib "records bound to calls of functions returning records"
  record Orientation "like MultiBody's Frames.Orientation"
    Real T[3, 3];
    Real w[3];
  end Orientation;

  record Frame2 "a nested record and a field default"
    Orientation R;
    Real scale = 1;
  end Frame2;

  function axisRotation
    input Integer axis;
    input Real angle;
    output Real T[3, 3];
  algorithm
    T := if axis == 1 then [1, 0, 0; 0, cos(angle), sin(angle); 0, -sin(angle), cos(angle)]
      elseif axis == 2 then [cos(angle), 0, -sin(angle); 0, 1, 0; sin(angle), 0, cos(angle)]
      else [cos(angle), sin(angle), 0; -sin(angle), cos(angle), 0; 0, 0, 1];
  end axisRotation;

  function axesRotations "a product of matrices returned in a record"
    input Integer sequence[3] = {1, 2, 3};
    input Real angles[3];
    input Real der_angles[3];
    output Orientation R;
  algorithm
    R := Orientation(T = axisRotation(sequence[3], angles[3]) * axisRotation(sequence[2], angles[2]) * axisRotation(sequence[1], angles[1]), w = der_angles);
  end axesRotations;

  function scaled "a record output changed field by field, a record input's field read"
    input Orientation R;
    input Real k;
    output Frame2 f;
  algorithm
    f := Frame2(R = R, scale = k);
    f.R.w := k * R.w;
  end scaled;
end RecordFunctionLib;

model RecordFunctionBindings "record parameters bound to function calls, evaluated at translation"
  import RecordFunctionLib.*;
  parameter Integer sequence[3] = {3, 1, 2};
  parameter Real angles[3] = {0.5, 0, 0};
  parameter Orientation R = axesRotations(sequence, angles, zeros(3)) "T: a rotation by 0.5 about axis 3";
  parameter Frame2 f = scaled(axesRotations(angles = {0, 0, 0.5}, der_angles = {1, 2, 3}), 2) "f.R.w = {2, 4, 6}";
  parameter Orientation R2 = if angles[1] > 0 then R else axesRotations(angles = zeros(3), der_angles = zeros(3)) "R itself";
  Real x(start = 1, fixed = true);
equation
  der(x) = -R.T[1, 2] * x + f.R.w[3] + R2.T[2, 1];
end RecordFunctionBindings;
