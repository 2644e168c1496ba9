#!/usr/bin/env python3
"""Stability (docs/BENCHMARKS.md, "Stability"): the stress suite's and the fuzzers' counts.

stability-counts.py BUILD OUT

Runs the stress suite (BUILD/tests/stress_test: rays along axes, through corners and edges,
grazing faces, cameras inside blocks and on boundaries, deep chains, wraps and rotations, far
origins, and the leak test) and `make fuzz-smoke` (each fuzz target for its seconds in the clang
build), and writes OUT/stability.md: per lookup, the rays tried, how many agreed with the exact
path, answered as a nearby ray, were capped or failed, the worst hit against the format's error
bound, the leaks, and per fuzz target its executions and crash files. Exit status 1 when the
stress suite or the fuzz run failed (the report is written first).
"""
import os
import re
import subprocess
import sys

SOURCE = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
RAYS = re.compile(r"^(.*), (exact|heuristic) lookup: (\d+) rays, (\d+) agreeing hits, (\d+) capped; (\d+) answers of a "
                  r"nearby ray \([^)]*\), (\d+) failures$")
BOUND = re.compile(r"worst hit within the format's bound at ([0-9.e+-]+) of it")
LEAKS = re.compile(r"leaks of the caster .*?: (\d+) in exact lookup, (\d+) in heuristic lookup; leaks of the exact "
                   r"path itself: (\d+) on the model")
AIMED = re.compile(r"^(\d+) rays aimed inside closed solids")


def stress(build):
    r = subprocess.run([os.path.join(build, "tests", "stress_test")], capture_output=True, text=True)
    totals = {m: {"scenes": 0, "rays": 0, "agreeing": 0, "nearby": 0, "capped": 0, "failures": 0} for m in ("exact", "heuristic")}
    worst_bound, leaks, model_leaks, aimed = 0.0, 0, 0, 0
    for line in r.stdout.splitlines():
        if m := RAYS.match(line):
            t = totals[m.group(2)]
            t["scenes"] += 1
            for key, group in (("rays", 3), ("agreeing", 4), ("capped", 5), ("nearby", 6), ("failures", 7)):
                t[key] += int(m.group(group))
        if m := BOUND.search(line):
            worst_bound = max(worst_bound, float(m.group(1)))
        if m := LEAKS.search(line):
            leaks += int(m.group(1)) + int(m.group(2))
            model_leaks += int(m.group(3))
        if m := AIMED.match(line):
            aimed += int(m.group(1))
    passed = re.search(r"\[  PASSED  \] (\d+) tests", r.stdout)
    return totals, worst_bound, leaks, model_leaks, aimed, r.returncode, passed.group(1) if passed else "0"


def fuzz():
    r = subprocess.run(["make", "--no-print-directory", "-C", SOURCE, "fuzz-smoke"], capture_output=True, text=True)
    rows, target = [], None
    for line in r.stderr.splitlines():
        if m := re.match(r"^fuzz: (\w+) for (\d+) s", line):
            target = {"target": m.group(1), "seconds": int(m.group(2)), "executions": 0}
            rows.append(target)
        elif (m := re.match(r"^stat::number_of_executed_units: (\d+)", line)) and target:
            target["executions"] += int(m.group(1))
    return rows, r.returncode


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    build, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    totals, worst_bound, leaks, model_leaks, aimed, stress_status, tests = stress(build)
    fuzz_rows, fuzz_status = fuzz()
    lines = [f"The stress suite: {tests} tests passed" + ("" if stress_status == 0 else ", and it FAILED") + ".\n",
             "| lookup | scenes | rays | agreeing hits | answers of a nearby ray | capped | failures |",
             "|---|---|---|---|---|---|---|"]
    for lookup, t in totals.items():
        lines.append(f"| {lookup} | {t['scenes']} | {t['rays']:,} | {t['agreeing']:,} | {t['nearby']:,} | {t['capped']:,} "
                     f"| {t['failures']:,} |")
    lines += ["",
              f"- Worst hit against the true model, as a share of the format's error bound: {worst_bound:.3g} "
              "(at most 1 is within the bound).",
              f"- The leak test: {aimed:,} rays aimed inside closed solids; {leaks} leaks of the caster, {model_leaks} "
              "of the exact path itself.",
              "", "The fuzz targets (`make fuzz-smoke`, the clang build with ASan and UBSan)"
              + ("" if fuzz_status == 0 else ": the run FAILED") + ":\n",
              "| target | seconds | executions |", "|---|---|---|"]
    lines += [f"| {r['target']} | {r['seconds']} | {r['executions']:,} |" for r in fuzz_rows]
    lines.append("\nCrash, leak, out-of-memory and timeout files left by the run: "
                 + ("none." if fuzz_status == 0 else "some (the run failed)."))
    with open(os.path.join(out, "stability.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"stability-counts: {out}/stability.md", file=sys.stderr)
    sys.exit(0 if stress_status == 0 and fuzz_status == 0 else 1)


if __name__ == "__main__":
    main()
