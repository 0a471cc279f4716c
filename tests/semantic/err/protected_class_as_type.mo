// expect: E2022 @9:5
package P
protected
  model Hidden
    Real x = 1;
  end Hidden;
end P;
model M
  P.Hidden h;
end M;
