/* A block comment at the start of the file.
   It spans several lines and may contain // without starting a line comment,
   as well as "quotes" and 'apostrophes'. */
// A line comment.
within; // a comment after the within clause

model CommentsAndStrings "Description made of " + "concatenated strings"
  parameter String plain = "plain text";
  parameter String quote = "a\"b\n" "Escaped double quote and newline";
  parameter String tab = "column1\tcolumn2";
  parameter String backslash = "C:\\temp\\file.txt";
  parameter String single = "it\'s and it's";
  parameter String others = "question\? bell\a backspace\b formfeed\f return\r vtab\v";
  parameter String multiLine = "first line
second line";
  parameter String joined = plain + ", " + tab + "!";
  parameter String empty = "";
  parameter String notAComment = "// not a comment /* neither */";
  Real x(start = 1 /* comment inside a modifier */, fixed = true); // trailing comment
  Real /* comment between type and name */ y;
equation
  // comment in an equation section
  der(x) = /* comment inside an expression */ -x "Equation with a description";
  y = 2 * x; /* block comment after an equation */
  assert(x >= 0, "x must be non-negative, got " + String(x) + "\n");
end CommentsAndStrings; // comment after end

/*
 * Comment between two classes.
 */
function greet "Builds a greeting"
  input String name = "world";
  output String text;
algorithm
  text := "Hello, " + name + "!\n"; // string concatenation with +
end greet;
