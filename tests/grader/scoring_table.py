#!/usr/bin/env python3
"""Old (per-check) and new (per-mistake) scores side by side, per submission, for the Markdown
table in docs/grading-reference.md ("Points follow mistakes").

Grades each set of submissions twice as a batch (`clothref grade DIR... --out BATCH`): once with
a rubric {"scoring": "per-check"}, once with the default rubric (per-mistake), then reads the
batches' grades.csv and each submission's results.json and prints, per set, one row per
submission: its two totals, the change, and each stub whose score changed with the mistake the
report names for it. It also checks that the batch CSV, row.json and results.json agree on every
score (total and per stub), that the tests' points add up to the total, and that both gradings
found the same failed checks and causes (the probes are deterministic: a difference is a timeout
under load, and the row says so).

Usage: scoring_table.py [--clothref build/bin/clothref] [--work build/scoring-table]
                        [--jobs 1] [--timeout 60] [--regrade] [SET ...]
  SET       a name and a glob of submission folders below the repository, as NAME=GLOB
            (default: corpus=tests/grader/corpus/20*/* handwritten=tests/grader/handwritten/20*/*
            blind=tests/grader/blind/20*/* blind2=tests/grader/blind2/20*/*)
  --work    where the batches go (WORK/<set>-per-check, WORK/<set>-per-mistake); a batch skips
            the submissions it already graded, so pass --regrade (or a new folder) after the
            grader changed
Exit 0 when every check holds, 1 otherwise (one line per problem on stderr); the tables go to
stdout either way.
"""
import argparse
import csv
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_SETS = ["corpus=tests/grader/corpus/20*/*", "handwritten=tests/grader/handwritten/20*/*",
                "blind=tests/grader/blind/20*/*", "blind2=tests/grader/blind2/20*/*"]
MODES = ["per-check", "per-mistake"]
# The rubric's line on a stub scored per mistake: one proven mistake, or several whose deductions
# add up ("2 proven mistakes (`a`, `b`) explain ...: together they lose 25 + 50 = 75 % ...").
NOTE = re.compile(r"(?:One mistake|[0-9]+ proven mistakes) \(([^)]+)\) explains? every failed "
                  r"check of this stub: (?:it loses|together they lose) ([0-9.]+(?: \+ [0-9.]+)*"
                  r"(?: = [0-9.]+)?) % of its points once")


def points(value):
    """Points as the grader shows them: rounded to 0.001, no trailing zeros."""
    text = f"{round(value, 3):.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def grade(clothref, dirs, batch, rubric, args):
    command = [str(clothref), "grade", *map(str, dirs), "--out", str(batch), "--no-whole-run",
               "--jobs", str(args.jobs), "--timeout", str(args.timeout), "--quiet",
               "--cache-dir", str(args.work / "cache")]
    if rubric:
        command += ["--rubric", str(rubric)]
    if args.regrade:
        command.append("--regrade")
    subprocess.run(command, check=True)


def read_batch(batch, problems):
    """submission -> {edition, total, stubs, tests, notes} from grades.csv, row.json and
    results.json, checking that the three agree."""
    rows = {}
    with open(batch / "grades.csv", newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            rows[row["submission"]] = row
    out = {}
    for name, row in sorted(rows.items()):
        folder = batch / name
        where = f"{batch.name}/{name}"
        try:
            results = json.loads((folder / "results.json").read_text(encoding="utf-8"))
            row_json = json.loads((folder / "row.json").read_text(encoding="utf-8"))
        except (OSError, ValueError) as error:
            problems.append(f"{where}: {error}")
            continue
        extra = results.get("extra_data", {})
        stubs = extra.get("stub_scores", {})
        total = results.get("score", 0)
        tests = results.get("tests", [])
        summed = sum(t["score"] for t in tests)
        if points(float(row["total"])) != points(total):
            problems.append(f"{where}: grades.csv total {row['total']}, results.json {total}")
        if points(row_json["total"]) != points(total):
            problems.append(f"{where}: row.json total {row_json['total']}, results.json {total}")
        if points(summed) != points(total):
            problems.append(f"{where}: the tests add up to {points(summed)}, the score is {total}")
        for stub, score in stubs.items():
            for source, value in (("grades.csv", row.get(stub)),
                                  ("row.json", row_json["stub_scores"].get(stub))):
                if value in (None, "") or points(float(value)) != points(score):
                    problems.append(f"{where}: {stub}: {source} {value}, results.json {score}")
            in_tests = sum(t["score"] for t in tests if t["tags"][0] == stub)
            if points(in_tests) != points(score):
                problems.append(f"{where}: {stub}: tests add up to {points(in_tests)}, not {score}")
        notes = {}
        for t in tests:
            found = NOTE.search(t.get("output", ""))
            if found:
                notes[t["tags"][0]] = (found.group(1), found.group(2))
        out[name] = {"edition": row["edition"], "total": total, "stubs": stubs, "notes": notes,
                     "failed": [(t["name"], tuple(t["tags"])) for t in tests
                                if t["status"] == "failed"]}
    return out


def table(name, old, new, problems):
    lines = [f"**{name}** ({len(new)} submissions)", "",
             "| submission | edition | per-check | per-mistake | change | stubs that changed (the mistake) |",
             "|---|---|---|---|---|---|"]
    changed = stubs_changed = 0
    sum_old = sum_new = 0.0
    for submission in sorted(set(old) | set(new)):
        if submission not in old or submission not in new:
            problems.append(f"{name}/{submission}: graded in one batch only")
            continue
        a, b = old[submission], new[submission]
        sum_old += a["total"]
        sum_new += b["total"]
        why = []
        for stub in sorted(set(a["stubs"]) | set(b["stubs"])):
            before, after = a["stubs"].get(stub, 0), b["stubs"].get(stub, 0)
            if points(before) == points(after):
                continue
            stubs_changed += 1
            note = b["notes"].get(stub)
            cause = f"{note[0]}, {note[1]} %" if note else "no per-mistake line"
            why.append(f"`{stub}` {points(before)} → {points(after)} ({cause})")
        if a["failed"] != b["failed"]:
            why.append("**the two gradings found different checks failing** (a timeout?)")
            problems.append(f"{name}/{submission}: the two gradings differ in their failed checks")
        delta = b["total"] - a["total"]
        changed += 1 if points(delta) != "0" else 0
        lines.append(f"| {submission} | {b['edition']} | {points(a['total'])} | "
                     f"{points(b['total'])} | {'+' if delta > 0 else ''}{points(delta)} | "
                     f"{'; '.join(why) if why else '—'} |")
    count = max(1, len(new))
    lines += ["", f"Mean total {points(sum_old / count)} per check, {points(sum_new / count)} per "
              f"mistake (of 80); {changed} of {len(new)} submissions and {stubs_changed} stubs "
              "changed.", ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("sets", nargs="*", metavar="SET", default=DEFAULT_SETS)
    parser.add_argument("--clothref", type=Path, default=ROOT / "build" / "bin" / "clothref")
    parser.add_argument("--work", type=Path, default=ROOT / "build" / "scoring-table")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--regrade", action="store_true")
    args = parser.parse_args()
    args.work = args.work.resolve()
    args.work.mkdir(parents=True, exist_ok=True)
    per_check = args.work / "per-check.json"
    per_check.write_text('{"scoring": "per-check"}\n', encoding="utf-8")
    problems = []
    for spec in args.sets:
        name, _, pattern = spec.partition("=")
        dirs = sorted(p for p in ROOT.glob(pattern) if p.is_dir())
        if not dirs:
            problems.append(f"{name}: no folder matches {pattern}")
            continue
        batches = {mode: args.work / f"{name}-{mode}" for mode in MODES}
        grade(args.clothref, dirs, batches["per-check"], per_check, args)
        grade(args.clothref, dirs, batches["per-mistake"], None, args)
        read = {mode: read_batch(batch, problems) for mode, batch in batches.items()}
        print(table(name, read["per-check"], read["per-mistake"], problems))
    print("Checked: grades.csv, row.json and results.json agree on every total and stub score, "
          "and the tests add up to them." if not problems else
          f"{len(problems)} problems (stderr).")
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
