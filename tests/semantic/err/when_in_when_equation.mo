// expect: E1202 @6:5
model M
  discrete Real y(start = 0);
equation
  when time > 1 then
    when time > 2 then
      y = 1;
    end when;
  end when;
end M;
