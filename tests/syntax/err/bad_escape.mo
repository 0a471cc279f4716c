model A
  String s = "tab\qhere";
end A;
