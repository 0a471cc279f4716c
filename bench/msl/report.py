#!/usr/bin/env python3
"""Turns msl-check's results CSV into docs/results/msl.md (stdout): a table per package
of how far each example gets (parses, flattens, balanced, translates, initializes,
simulates, matches the reference), every failing example with its reason, and the
whole-process time per example."""
import csv, os, re, statistics, subprocess, sys, datetime

STAGES = ["parses", "flattens", "balanced", "translates", "initializes", "simulates", "matches"]
FIVE = ["Modelica.Blocks", "Modelica.Electrical.Analog", "Modelica.Mechanics.Rotational",
        "Modelica.Mechanics.Translational", "Modelica.Thermal.HeatTransfer"]


def reached(row):
    """The number of stages an example passed (7 = matches the reference)."""
    out, detail = row["outcome"], row["detail"]
    if out == "pass":
        return 7
    if out in ("mismatch",):
        return 6
    code = re.search(r"error\[(E\d+)\]", detail)
    code = code.group(1) if code else ""
    if code.startswith("E1"):
        return 0
    if code == "E2010":
        return 2
    if code.startswith("E2"):
        return 1
    if code.startswith("E3"):
        return 3
    if code == "E4001":
        return 4
    return 5  # failed while simulating (E4002, E4003, ...), timeout


def package(model):
    for p in FIVE + ["Modelica.Mechanics.MultiBody"]:
        if model.startswith(p + "."):
            return p
    return model.rsplit(".", 2)[0]


def has_reference(ref, model):
    """Whether the test data has the example's reference CSV (some folders hold only
    comparisonSignals.txt)."""
    folder = os.path.join(ref, *model.split("."))
    return os.path.exists(os.path.join(folder, model.rsplit(".", 1)[1] + ".csv"))


def passes(path, ref):
    """Examples of the five packages that match, in a results CSV."""
    return sum(1 for r in csv.DictReader(open(path))
               if r["outcome"] == "pass" and package(r["model"]) in FIVE and has_reference(ref, r["model"]))


def main(path, ref, every_step_path=None, timefix_path=None):
    every = list(csv.DictReader(open(path)))
    rows = [r for r in every if r["outcome"] != "no-reference" and has_reference(ref, r["model"])]
    absent = [r for r in every if r["outcome"] == "no-reference" or not has_reference(ref, r["model"])]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    print("# MSL 4.1.0: examples against the reference results\n")
    print(f"Measured {datetime.date.today()} on commit `{commit}` with `bash bench/msl/run.sh` "
          "(release build, this machine: 2 cores, shared). The criterion is "
          "`../shared/tools/msl-check`'s: every compared signal within 0.2 % of its "
          "range at the reference's time points, rows next to jumps left out; the "
          "experiment annotation of each example drives the run. The command is "
          "msl-check's default (`unimo simulate ... --vars ... --output ...`): rows on the "
          "experiment's output grid, two at each event, and between the grid's points the "
          "solver steps a straight line between rows would misstate by more than 1e-3 of "
          "a state's magnitude (`--output-tolerance`, docs/simulate.md). msl-check "
          "interpolates the result linearly between rows, and the references were written "
          "on grids denser than the examples' own `Interval` (SimpleGearShift: Interval "
          "0.01, reference every 0.005). Times are the whole process (load, translate, "
          "simulate, write).\n")
    by_pkg = {}
    for r in rows:
        by_pkg.setdefault(package(r["model"]), []).append(r)
    print("| package | examples | " + " | ".join(STAGES) + " |")
    print("|---|---|" + "---|" * len(STAGES))
    tot = [0] * len(STAGES)
    n_five = 0
    pass_five = 0
    for p in sorted(by_pkg):
        rs = by_pkg[p]
        counts = [sum(1 for r in rs if reached(r) > k) for k in range(len(STAGES))]
        if p in FIVE:
            n_five += len(rs)
            pass_five += counts[-1]
        tot = [a + b for a, b in zip(tot, counts)]
        print(f"| {p} | {len(rs)} | " + " | ".join(map(str, counts)) + " |")
    print(f"| **all** | {len(rows)} | " + " | ".join(map(str, tot)) + " |\n")
    n_absent = sum(1 for r in absent if package(r["model"]) in FIVE)
    total = n_five + n_absent
    print(f"The five packages of the acceptance (Blocks, Electrical.Analog, Rotational, "
          f"Translational, HeatTransfer): **{pass_five} of {total}** match the reference "
          f"({100.0 * pass_five / max(total, 1):.0f} %; {n_absent} of the {total} have no "
          f"reference CSV in the test data and cannot pass msl-check).\n")
    if every_step_path:
        print(f"With a row after every solver step (`--every-step` through msl-check's "
              f"`--cmd`): **{passes(every_step_path, ref)} of {total}**; the difference is "
              f"interpolation between rows, the simulation is the same.\n")
    times = [float(r["seconds"]) for r in rows if r["outcome"] == "pass"]
    if times:
        print(f"Whole-process time of the passing examples: median {statistics.median(times)*1000:.0f} ms, "
              f"largest {max(times)*1000:.0f} ms.\n")
    if absent:
        print("Without a reference CSV in the test data (not counted): " +
              ", ".join(f"`{r['model']}`" for r in absent) + ".\n")
    unreadable = [r for r in rows if "unreadable: 'time'" in r["detail"]]
    if unreadable:
        fixed = {}
        if timefix_path:
            fixed = {r["model"]: r for r in csv.DictReader(open(timefix_path))}
        match = [r for r in unreadable if fixed.get(r["model"], {}).get("outcome") == "pass"]
        in_five = [r for r in match if package(r["model"]) in FIVE]
        print("msl-check reads the column `time`; the reference CSVs of " +
              ", ".join(f"`{r['model'][9:]}`" for r in unreadable) +
              " name it `Time`, so msl-check cannot compare them and counts them as "
              "mismatches. Compared by msl-check on a copy of those references with the "
              f"column renamed `time` (nothing else changed), **{len(match)} of "
              f"{len(unreadable)}** match: " +
              ", ".join(f"`{r['model'][9:]}`" for r in match) +
              f". Counting them, {pass_five + len(in_five)} of {total} of the five "
              f"packages match ({100.0 * (pass_five + len(in_five)) / max(total, 1):.0f} %).\n")
    short = [r for r in rows if "result ends at" in r["detail"]]
    if short:
        print("The reference results of " + ", ".join(f"`{r['model'][9:]}`" for r in short) +
              " run past the stop time of the example's own `experiment` annotation "
              "(which unimo follows, as the issue asks); they cannot match.\n")
    print("## Every example\n")
    print("| example | outcome | seconds | reason or worst signal |")
    print("|---|---|---|---|")
    for r in sorted(rows, key=lambda r: r["model"]):
        detail = r["detail"].replace("|", "\\|").replace("\n", " ")[:220]
        stage = STAGES[reached(r)] if reached(r) < 7 else "matches"
        outcome = "pass" if r["outcome"] == "pass" else f"fails: {stage}"
        print(f"| `{r['model'][9:]}` | {outcome} | {r['seconds']} | {detail} |")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], *[a or None for a in sys.argv[3:5]])
