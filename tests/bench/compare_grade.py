#!/usr/bin/env python3
"""Two builds of the grader graded on the same submissions, alternating, in one sitting
(docs/performance.md, "Grading a class"): what one costs against the other as a ratio of medians
of busy CPU (the grader and every process it started: tests/bench/busy_cpu.py), which the
machine's load disturbs less than a figure of another day.

Each grade starts from an empty object cache (what a distinct submission of a batch costs), on a
copy of the submission with a comment added to each file (our reference's files would otherwise
match the objects clothref prebuilt, and no compile would be measured); the order within a pair
alternates (old, new; new, old; ...) so a change of load hits both alike.

Usage: tests/bench/compare_grade.py OLD_BUILD NEW_BUILD SUBMISSION... [--pairs N]
Prints each run, then per submission the medians, the ratio new / old and the load around it.
A benchmark, not a test.
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from busy_cpu import BusyCpu, load, yardstick  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("submissions", nargs="+")
    parser.add_argument("--pairs", type=int, default=5)
    args = parser.parse_args()
    builds = {}
    for label, build in (("old", args.old), ("new", args.new)):
        clothref = os.path.join(os.path.abspath(build), "bin", "clothref")
        if not os.access(clothref, os.X_OK):
            sys.exit(f"compare_grade: {clothref} not built")
        builds[label] = clothref
    for submission in args.submissions:
        if not os.path.isdir(submission):
            sys.exit(f"compare_grade: {submission}: not a folder")
    cpu = BusyCpu()
    work = tempfile.mkdtemp(prefix="clothref-compare-")
    try:
        print(f"busy CPU by {cpu.how}; {load()}; yardstick {yardstick(cpu):.2f} s", flush=True)
        for number, original in enumerate(args.submissions):
            submission = os.path.join(work, f"submission-{number}")
            shutil.copytree(original, submission)
            for dirpath, _, files in os.walk(submission):
                for name in files:
                    if name.endswith(".cpp"):
                        with open(os.path.join(dirpath, name), "a") as handle:
                            handle.write("\n// compare_grade: a distinct copy\n")
            busy = {"old": [], "new": []}
            for pair in range(args.pairs):
                order = ("old", "new") if pair % 2 == 0 else ("new", "old")
                for label in order:
                    cache = os.path.join(work, "cache")
                    shutil.rmtree(cache, ignore_errors=True)
                    results = os.path.join(work, f"{label}-{pair}.json")
                    code, wall, seconds = cpu.run(
                        [builds[label], "grade", submission, "--cache-dir", cache, "--results",
                         results], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                    if code != 0:
                        sys.exit(f"compare_grade: {label} exited {code} on {original}")
                    busy[label].append(seconds)
                    print(f"  pair {pair + 1} {label}: busy CPU {seconds:6.2f} s, wall {wall:6.2f} s",
                          flush=True)
            old, new = statistics.median(busy["old"]), statistics.median(busy["new"])
            print(f"{original}: busy CPU median old {old:.2f} s, new {new:.2f} s, new / old "
                  f"{new / old:.2f} ({args.pairs} pairs); {load()}; yardstick "
                  f"{yardstick(cpu):.2f} s", flush=True)
    finally:
        cpu.close()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
