#!/usr/bin/env python3
"""Rewrites the generated sections of docs/BENCHMARKS.md from a `make bench` run.

bench_report.py REPORT NAME=FILE [NAME=FILE ...]

A generated section lies between the lines `<!-- make bench: NAME -->` and
`<!-- end make bench: NAME -->`. Its text is replaced by FILE's, after a line that says where and
when it was measured: the CPU, its cores, the commit and the date. The report is written to a
temporary file and renamed. Exit status 1 when a section named is not in the report.
"""
import datetime
import os
import re
import subprocess
import sys


def machine():
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            found = re.search(r"^model name\s*:\s*(.*)$", f.read(), re.M)
            model = found.group(1).strip() if found else model
    except OSError:
        pass
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    # The run writes the report and its plots under docs/ itself: changes elsewhere are the code's.
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", ".", ":(exclude)docs"],
                           capture_output=True, text=True).stdout.strip()
    return (f"*Measured on {datetime.date.today().isoformat()}: {model}, {os.cpu_count()} cores, "
            f"commit {commit or 'unknown'}{' with local changes' if dirty else ''}.*")


def main():
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    report = sys.argv[1]
    with open(report) as f:
        text = f.read()
    stamp = machine()
    for arg in sys.argv[2:]:
        name, path = arg.split("=", 1)
        begin, end = f"<!-- make bench: {name} -->\n", f"<!-- end make bench: {name} -->"
        start = text.find(begin)
        stop = text.find(end, start)
        if start < 0 or stop < 0:
            print(f"bench_report: {report}: no section '{name}'", file=sys.stderr)
            sys.exit(1)
        with open(path) as f:
            body = f.read().rstrip("\n")
        text = text[:start + len(begin)] + stamp + "\n\n" + body + "\n" + text[stop:]
    temporary = report + ".tmp"
    with open(temporary, "w") as f:
        f.write(text)
    os.replace(temporary, report)
    print(f"bench_report: rewrote {', '.join(a.split('=')[0] for a in sys.argv[2:])} in {report}", file=sys.stderr)


if __name__ == "__main__":
    main()
