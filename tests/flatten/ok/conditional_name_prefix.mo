// An absent conditional connector `V` drops its own connections only: `V_internal`,
// whose name starts with `V`, keeps its connection to the constant (spec 4.4.5).
package NamePrefix
  connector RealInput = input Real;
  connector RealOutput = output Real;

  block Constant
    parameter Real k = 1;
    RealOutput y;
  equation
    y = k;
  end Constant;

  model Source
    parameter Boolean useConstant = true;
    RealInput V if not useConstant;
    Real v;
  protected
    RealInput V_internal;
    Constant V_constant(k = 2) if useConstant;
  equation
    connect(V, V_internal);
    connect(V_constant.y, V_internal);
    v = 3 * V_internal;
  end Source;
end NamePrefix;

model ConditionalNamePrefix
  NamePrefix.Source source;
end ConditionalNamePrefix;
