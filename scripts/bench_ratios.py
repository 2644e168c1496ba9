#!/usr/bin/env python3
"""The pinned ratios of docs/BENCHMARKS.md, and the guard of make bench-quick.

bench_ratios.py RESULTS_DIR [--pinned bench/pinned_ratios.json] [--programs P,...] [--write-baseline]
bench_ratios.py --filters [--pinned ...]

Reads the Google Benchmark JSON files RESULTS_DIR/PROGRAM.json, takes for each pinned ratio the
median of the numerator's and of the denominator's repetitions (or their single run), and prints
one line per ratio in a fixed form that scripts can read:

    NUT/fastest Embree rays/s (building, 1 thread): 0.31 (goal >= 1.5; baseline 0.32, guard 0.19)

A denominator given as a list is the peer at its best: the highest of their medians (the fastest
of Embree's ray modes).

Exit status 1 when a ratio is below its guard, baseline x (1 - margin), naming it on stderr; 2
when a result is missing. --programs checks only the ratios of those programs; --write-baseline
stores the measured ratios as the new baselines. --filters prints, per program, the
--benchmark_filter that runs just the benchmarks the ratios need: "PROGRAM REGEX" a line.
"""
import argparse
import json
import os
import re
import statistics
import sys


def median_metric(results, name, metric):
    runs = [b for b in results.get("benchmarks", []) if b.get("run_name", b["name"]) == name
            and b.get("run_type", "iteration") == "iteration"]
    values = [b[metric] for b in runs if metric in b]
    if not values:
        raise KeyError(name)
    return statistics.median(values)


def denominators(ratio):
    d = ratio["denominator"]
    return d if isinstance(d, list) else [d]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results", nargs="?")
    parser.add_argument("--filters", action="store_true", help="print each program's benchmark filter")
    parser.add_argument("--pinned", default=os.path.join(os.path.dirname(__file__), "..", "bench", "pinned_ratios.json"))
    parser.add_argument("--programs", help="only the ratios of these programs (comma-separated)")
    parser.add_argument("--write-baseline", action="store_true")
    args = parser.parse_args()
    with open(args.pinned) as f:
        pinned = json.load(f)
    if args.filters:
        names = {}
        for ratio in pinned["ratios"]:
            names.setdefault(ratio["program"], set()).update([ratio["numerator"], *denominators(ratio)])
        for program, wanted in names.items():
            print(program, "^(" + "|".join(re.escape(n) for n in sorted(wanted)) + ")$")
        return 0
    if args.results is None:
        parser.error("RESULTS_DIR is required")
    loaded = {}
    regressed = []
    wanted = set(args.programs.split(",")) if args.programs else None
    for ratio in pinned["ratios"]:
        program = ratio["program"]
        if wanted is not None and program not in wanted:
            continue
        if program not in loaded:
            path = os.path.join(args.results, program + ".json")
            try:
                with open(path) as f:
                    loaded[program] = json.load(f)
            except (OSError, ValueError) as error:
                print(f"bench_ratios: {path}: {error}", file=sys.stderr)
                return 2
        try:
            value = (median_metric(loaded[program], ratio["numerator"], ratio["metric"]) /
                     max(median_metric(loaded[program], d, ratio["metric"]) for d in denominators(ratio)))
        except KeyError as missing:
            print(f"bench_ratios: {program}.json has no {ratio['metric']} for {missing}", file=sys.stderr)
            return 2
        baseline = ratio.get("baseline")
        if args.write_baseline:
            ratio["baseline"] = round(value, 4)
            baseline = ratio["baseline"]
        guard = None if baseline is None else baseline * (1 - ratio["margin"])
        line = f"{ratio['name']}: {value:.3g} (goal >= {ratio['goal']:g}"
        line += "; no baseline)" if guard is None else f"; baseline {baseline:.3g}, guard {guard:.3g})"
        if guard is not None and value < guard:
            line += " REGRESSED"
            regressed.append(ratio["name"])
        print(line)
    if args.write_baseline:
        with open(args.pinned + ".tmp", "w") as f:
            json.dump(pinned, f, indent=1)
            f.write("\n")
        os.replace(args.pinned + ".tmp", args.pinned)
        print(f"bench_ratios: baselines written to {args.pinned}", file=sys.stderr)
    for name in regressed:
        print(f"bench_ratios: regressed past its margin: {name}", file=sys.stderr)
    return 1 if regressed else 0


if __name__ == "__main__":
    sys.exit(main())
