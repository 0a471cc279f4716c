model StatelessTimeEvents "A periodic counter with no continuous state (the MSL's pulse sources): its when fires at t = startTime + k * period"
  parameter Real period = 0.1;
  parameter Real startTime = -0.035;
  discrete Integer count;
  discrete Real T_start;
initial algorithm
  count := integer((time - startTime) / period);
  T_start := startTime + count * period;
equation
  when time >= (pre(count) + 1) * period + startTime then
    count = pre(count) + 1;
    T_start = time;
  end when;
end StatelessTimeEvents;
