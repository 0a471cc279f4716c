// Quoted identifiers for classes, components and record fields,
// including names containing spaces, dots, operators and keywords.
model 'Quoted Model' "A model whose name is quoted"
  parameter Real 'my param' = 2;
  Real 'my var'(start = 1, fixed = true);
  Real 'x.y' "Quoted name containing a dot";
  Real '1st' "Quoted name starting with a digit";
  Real 'for' "Quoted name spelled like a keyword";
  Real 'it\'s' "Quoted name with an escaped apostrophe";
  Real normal;
equation
  der('my var') = -'my param' * 'my var';
  'x.y' = 2 * 'my var';
  '1st' = 'x.y' + 1;
  'for' = '1st' - 'x.y';
  'it\'s' = 'for';
  normal = 'it\'s' + 'my var';
end 'Quoted Model';

record 'Data Set' "A record with quoted fields"
  Real 'field one' = 1;
  Real 'field+two' = 2;
  Real 'a[1]' = 3 "Brackets are part of the name";
end 'Data Set';

model UsesQuoted "References through quoted names"
  'Quoted Model' 'inner model';
  'Data Set' 'data'('field one' = 10);
  Real total;
  Real 'result (W)';
equation
  total = 'inner model'.'my var' + 'data'.'field one' + 'data'.'field+two';
  'result (W)' = total * 'data'.'a[1]';
end UsesQuoted;
