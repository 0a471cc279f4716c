// expect: E2021 @7:8
package Types
  type Phase = enumeration(A, B, C);
end Types;
connector Port
  Real v;
  flow Types.Phase p;
end Port;
