#!/usr/bin/env python3
"""Turns out/results.tsv (written by run.sh) into the markdown report on stdout.

Usage: make_table.py OUT_DIR RUNS SCIPY_RUNS [BRUSS_RUNS [ROUNDS]]

A configuration measured in several rounds has one row per round in results.tsv: its time
is the median of the rounds' times (each a median of RUNS runs); its digits and steps are
the first round's (the runs are deterministic; a round that disagrees is reported).
"""
import sys
from pathlib import Path

out = Path(sys.argv[1])
runs, scipy_runs = sys.argv[2], sys.argv[3]
bruss_runs = sys.argv[4] if len(sys.argv) > 4 else runs
rounds = int(sys.argv[5]) if len(sys.argv) > 5 else 1
PROBLEMS = ["ROBER", "HIRES", "VDPOL", "POLLU", "BRUSS2D"]
TOOLS = ["unimo", "IDA", "diffsol", "SciPy"]

rows = []
for line in (out / "results.tsv").read_text().splitlines():
    f = line.split("\t")
    if len(f) < 9:
        continue
    problem, tool, method, rtol, atol, scd, steps, ms = f[:8]
    status = "\t".join(f[8:])
    rows.append(dict(problem=problem, tool=tool, method=method, rtol=float(rtol),
                     atol=float(atol), scd=scd, steps=steps, ms=float(ms), status=status))

# One row per configuration: the median of its rounds' times.
merged = {}
for r in rows:
    key = (r["problem"], r["tool"], r["method"], r["rtol"])
    if key not in merged:
        merged[key] = dict(r, times=[r["ms"]])
        continue
    m = merged[key]
    m["times"].append(r["ms"])
    if (r["scd"], r["steps"], r["status"]) != (m["scd"], m["steps"], m["status"]):
        note = f"round {len(m['times'])}: {r['scd']} scd, {r['steps']} steps, {r['status']}"
        m["status"] = m["status"] + f" (differs in {note})"
for m in merged.values():
    t = sorted(m["times"])
    k = len(t)
    m["ms"] = t[k // 2] if k % 2 else (t[k // 2 - 1] + t[k // 2]) / 2
rows = list(merged.values())

method_order = {}
for r in rows:
    method_order.setdefault((r["tool"], r["method"]), len(method_order))
rows.sort(key=lambda r: (PROBLEMS.index(r["problem"]), TOOLS.index(r["tool"]),
                         method_order[(r["tool"], r["method"])], -r["rtol"]))


def cell(s):
    return s.replace("|", "\\|")


def ok(r):
    return r is not None and r["status"] == "ok"


def reference_rtols(prow):
    """The tolerances the other tools ran at (unimo also runs between them, for the table
    at equal digits)."""
    return sorted({r["rtol"] for r in prow if r["tool"] != "unimo"}, reverse=True)


def section(title, intro, columns):
    """A report section's title, its introduction and its table's header rows."""
    print(f"## {title}\n")
    print(intro + "\n")
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))


def ida_analytic(prow, rtol):
    """IDA's run with the analytic Jacobian at `rtol` among a problem's rows."""
    return next((r for r in prow if r["tool"] == "IDA" and r["rtol"] == rtol
                 and "analytic" in r["method"]), None)


def find(problem, tool, method, rtol):
    for r in rows:
        if (r["problem"], r["tool"], r["method"], r["rtol"]) == (problem, tool, method, rtol):
            return r
    return None


def verdict():
    """Issue #23's point 4, cell by cell: our best method against diffsol's BDF (digits, then
    time) and against IDA with its analytic Jacobian (time), and whether we failed."""
    section("Point 4 of issue #23, per problem and tolerance",
            "Our best method: of unimo's methods that reach at least diffsol BDF's scd (all of"
            " them where diffsol fails), the fastest; where none does, the one with the most"
            " digits. Ratios are time(other) / time(ours): above 1, we are faster. The claim"
            " holds in a cell when ours has scd >= diffsol BDF's and ratio >= 1 (or diffsol"
            " failed), ratio to IDA >= 3, and no unimo method failed.",
            ["problem", "rtol", "ours: method, scd / ms", "diffsol bdf: scd / ms",
             "vs diffsol", "IDA (analytic): scd / ms", "vs IDA", "unimo failures", "point 4"])
    for p in PROBLEMS:
        prow = [r for r in rows if r["problem"] == p]
        for rtol in reference_rtols(prow):
            ours = [r for r in prow if r["tool"] == "unimo" and r["rtol"] == rtol]
            good = [r for r in ours if ok(r)]
            failures = [r["method"] for r in ours if not ok(r)]
            ds = find(p, "diffsol", "bdf", rtol)
            ida = ida_analytic(prow, rtol)
            if not good:
                print(f"| {p} | {rtol:.0e} | all failed | | | | | {', '.join(failures)} | no |")
                continue
            target = float(ds["scd"]) if ok(ds) else None
            reaching = [r for r in good if target is None or float(r["scd"]) >= target]
            best = min(reaching, key=lambda r: r["ms"]) if reaching \
                else max(good, key=lambda r: float(r["scd"]))
            holds = not failures
            if ok(ds):
                vs_ds = ds["ms"] / best["ms"]
                ds_cell, vs_ds_cell = f"{float(ds['scd']):.2f} / {ms(ds['ms'])}", f"{vs_ds:.2f}x"
                holds = holds and float(best["scd"]) >= target and vs_ds >= 1.0
            else:
                ds_cell, vs_ds_cell = ("FAILED" if ds else "-"), "-"
            if ok(ida):
                vs_ida = ida["ms"] / best["ms"]
                ida_cell, vs_ida_cell = f"{float(ida['scd']):.2f} / {ms(ida['ms'])}", f"{vs_ida:.2f}x"
                holds = holds and vs_ida >= 3.0
            else:
                ida_cell, vs_ida_cell = ("FAILED" if ida else "-"), "-"
            print(f"| {p} | {rtol:.0e} | {best['method']}, {float(best['scd']):.2f} / {ms(best['ms'])}"
                  f" | {ds_cell} | {vs_ds_cell} | {ida_cell} | {vs_ida_cell} |"
                  f" {', '.join(failures) or 'none'} | {'yes' if holds else 'no'} |")
    print()


def fastest_reaching(prow, target):
    """Our fastest run, of any method and tolerance, with at least `target` digits."""
    reaching = [r for r in prow if r["tool"] == "unimo" and ok(r) and float(r["scd"]) >= target]
    return min(reaching, key=lambda r: r["ms"]) if reaching else None


def verdict_equal_digits():
    """Point 4 read as work against precision: for each cell of diffsol's BDF and of IDA,
    our fastest measured run that reaches at least its digits."""
    section("Point 4 at equal digits",
            "The same cells read as work against precision: against each run of diffsol's BDF"
            " and of IDA (analytic Jacobian), our fastest measured run, of any method and"
            " tolerance (unimo also ran at the tolerances between the columns), with at least"
            " its digits. Ratios are time(other) / time(ours). The cell holds when the ratio to"
            " diffsol is >= 1 (or diffsol failed), the ratio to IDA >= 3, and no unimo run of"
            " the problem failed. Measured, not interpolated: every time in this table is a"
            " row of \"All results\".",
            ["problem", "rtol", "diffsol bdf: scd / ms", "ours with >= its digits",
             "vs diffsol", "IDA: scd / ms", "ours with >= its digits", "vs IDA",
             "unimo failures", "holds"])
    for p in PROBLEMS:
        prow = [r for r in rows if r["problem"] == p]
        failures = sorted({f"{r['method']} {r['rtol']:.0e}" for r in prow
                           if r["tool"] == "unimo" and not ok(r)})
        for rtol in reference_rtols(prow):
            holds = not failures
            cells = []
            for tool, method, factor in (("diffsol", "bdf", 1.0), ("IDA", "analytic", 3.0)):
                ref = find(p, tool, method, rtol) if tool == "diffsol" else ida_analytic(prow, rtol)
                if not ok(ref):
                    cells += ["FAILED" if ref else "-", "-", "-"]
                    continue
                ours = fastest_reaching(prow, float(ref["scd"]))
                if ours is None:
                    cells += [f"{float(ref['scd']):.2f} / {ms(ref['ms'])}", "none", "-"]
                    holds = False
                    continue
                ratio = ref["ms"] / ours["ms"]
                holds = holds and ratio >= factor
                cells += [f"{float(ref['scd']):.2f} / {ms(ref['ms'])}",
                          f"{ours['method']} {ours['rtol']:.0e}: {float(ours['scd']):.2f} / {ms(ours['ms'])}",
                          f"{ratio:.2f}x"]
            print(f"| {p} | {rtol:.0e} | " + " | ".join(cells) +
                  f" | {', '.join(failures) or 'none'} | {'yes' if holds else 'no'} |")
    print()


def ms(x):
    return f"{x:.3f}" if x < 10 else f"{x:.1f}" if x < 1000 else f"{x:.0f}"


print("# unimo vs. IDA vs. diffsol vs. SciPy: error against run time\n")
print("Written by `bench/compare/run.sh` (see README.md there). scd = -log10(max_i |y_i - ref_i| / |ref_i|)"
      " at the end time; time = median wall time of "
      f"{runs} runs (SciPy: {scipy_runs} runs; BRUSS2D: {bruss_runs} runs, SciPy 1), all measured in"
      f" one session. ROBER, HIRES, VDPOL and POLLU ran in {rounds} rounds, each round unimo, IDA"
      " and diffsol one after the other (a slow stretch of the shared machine falls on every"
      " tool): their time is the median of the rounds' medians. BRUSS2D and SciPy ran once, one"
      " tool after the other.\n")
print((out / "versions.md").read_text())
print("Load average (1, 5, 15 min) read before each tool and round; the machine has 2 cores and was shared"
      " with other work, so times can be noisy:\n")
for line in (out / "load.txt").read_text().splitlines():
    print(f"- {line}")
print()
print("What each timing covers: unimo = its `simulate` call (initialisation, integration and the"
      " 2-row result; no model compilation, and the native code of `--engine native`, unimo"
      " bench's default, is compiled before the timed runs); IDA = create, init, solve to t_end, free;"
      " diffsol = build the problem, create the solver (consistent initialisation), step to t_end;"
      " SciPy = one `solve_ivp` call (Python-level right-hand side and Jacobian).\n")

print("## Summary: scd / median ms\n")
for p in PROBLEMS:
    prow = [r for r in rows if r["problem"] == p]
    if not prow:
        continue
    rtols = reference_rtols(prow)
    atol = {r["rtol"]: r["atol"] for r in prow}
    print(f"### {p}\n")
    print("| tool | method | " + " | ".join(f"rtol {t:.0e}, atol {atol[t]:.0e}" for t in rtols) + " |")
    print("|---|---|" + "---|" * len(rtols))
    keys = []
    for r in prow:
        if (r["tool"], r["method"]) not in keys:
            keys.append((r["tool"], r["method"]))
    for tool, method in keys:
        cells = []
        for t in rtols:
            m = [r for r in prow if r["tool"] == tool and r["method"] == method and r["rtol"] == t]
            if not m:
                cells.append("")
            elif m[0]["status"].startswith("NOT RUN"):
                cells.append("not run")
            elif m[0]["status"] != "ok":
                cells.append("FAILED")
            else:
                cells.append(f"{float(m[0]['scd']):.2f} / {ms(m[0]['ms'])}")
        print(f"| {tool} | {method} | " + " | ".join(cells) + " |")
    print()

verdict()
verdict_equal_digits()

print("## All results\n")
print("| problem | tool | method | rtol | atol | scd | steps | median ms | note |")
print("|---|---|---|---|---|---|---|---|---|")
for r in rows:
    failed = r["status"] != "ok"
    scd = ("not run" if r["status"].startswith("NOT RUN") else "FAILED") if failed \
        else f"{float(r['scd']):.2f}"
    note = cell(r["status"]) if failed else ""
    if failed and r["steps"] not in ("-", "") and not r["status"].startswith("NOT RUN"):
        note += f" (steps before the failure: {r['steps']}; time is that of the failing runs)"
    print(f"| {r['problem']} | {r['tool']} | {r['method']} | {r['rtol']:.0e} | {r['atol']:.0e} | "
          f"{scd} | {r['steps']} | {ms(r['ms'])} | {note} |")
