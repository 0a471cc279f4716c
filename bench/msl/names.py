#!/usr/bin/env python3
"""Appends to docs/results/msl.md the summary of `unimo check --no-balance` over every
MSL file: the syntax errors (there must be none) and each remaining name error, grouped
by the file and the name, with the reason it is reported."""
import collections, re, sys

REASONS = [
    ("Modelica/Clocked", "the predefined type `Clock` (clocked features are not implemented)"),
    ("Modelica/Media/Water/IF97_Utilities.mo", "the built-in `array(...)` constructor is "
     "not implemented"),
    ("Modelica/Fluid", "`Medium.saturationPressure` and the like, where `Medium` is "
     "redeclared in an extends modifier (`extends Base(redeclare package Medium = "
     "PartialTwoPhaseMedium)`): the name check looks them up in the base's declared "
     "`PartialMedium`, which lacks them (flattening follows the redeclaration)"),
]


def main(path):
    text = open(path).read()
    last = text.strip().splitlines()[-1] if text.strip() else ""
    errors = re.findall(r"error\[(E\d+)\]: ([^\n]*)\n\s*┌─ ([^:]+):", text)
    codes = collections.Counter(c for c, _, _ in errors)
    syntax = sum(n for c, n in codes.items() if c.startswith("E1"))
    print("\n## Names and syntax over every MSL file\n")
    print(f"`unimo check --no-balance --lib ../shared/msl ../shared/msl`: {last}. "
          f"Syntax errors: **{syntax}**. Remaining errors by code: " +
          ", ".join(f"{c} {n}" for c, n in sorted(codes.items())) + ".\n")
    groups = collections.Counter()
    for code, msg, file in errors:
        file = file.split("msl/", 1)[-1]
        reason = next((r for key, r in REASONS if key in file), "not analysed yet")
        groups[(reason, code)] += 1
    print("| errors | code | where and why |")
    print("|---|---|---|")
    for (reason, code), n in groups.most_common():
        print(f"| {n} | {code} | {reason} |")
    names = collections.Counter(re.sub(r".*`([^`]+)`.*", r"\1", m) for _, m, _ in errors)
    print("\nMost frequent names: " + ", ".join(f"`{k}` {v}" for k, v in names.most_common(12)) + ".")


if __name__ == "__main__":
    main(sys.argv[1])
