// expect: E2022 @9:13
package P
protected
  model Hidden
    Real x = 1;
  end Hidden;
end P;
model M
  extends P.Hidden;
end M;
