// expect: E2004 @3:13
model M
  Integer n(stateSelect = StateSelect.never) = 1;
end M;
