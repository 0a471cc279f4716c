// expect: E2025 @7:5
model M
  parameter Real p = 1;
  discrete Real x(start = 0);
algorithm
  when time > 1 then
    p := 2;
    x := p;
  end when;
end M;
