#!/usr/bin/env python3
"""Checks the grader corpus against the course stand-in headers: every case's three files (picked
as the grader does: below src/ when there is one, else anywhere) compile with
g++ -std=c++20 -fsyntax-only, except the files its expected.json lists under compile_errors, which
must not. Mutants with a "base" are completed from that submission first.

Usage: check_corpus.py [--course DIR] [--cxx g++] [CASE ...]
  --course  the stand-in (default tools/grader/course): DIR/<edition>/include, DIR/common/include
Exit 0 when every case behaves, 1 otherwise (one line per failing file on stderr).
"""
import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
FILES = ["cloth.cpp", "sphere.cpp", "integrator.cpp"]


def find_files(directory):
    """The three course files below `directory`, preferring those under a src/ folder."""
    found = {}
    for name in FILES:
        candidates = sorted(directory.rglob(name))
        in_src = [c for c in candidates if "src" in c.relative_to(directory).parts]
        pick = (in_src or candidates or [None])[0]
        if pick is not None:
            found[name] = pick
    return found


def materialise(case, scratch):
    """Directory holding the case's submission: the case itself, or its base overlaid with it."""
    expected = json.loads((case / "expected.json").read_text())
    if "base" not in expected:
        return case, expected
    target = scratch / case.parent.name / case.name
    base_files = find_files(HERE / expected["base"])
    own = find_files(case)
    target.mkdir(parents=True)
    for name in FILES:
        shutil.copyfile(own.get(name, base_files[name]), target / name)
    return target, expected


def compiles(cxx, course, edition, path):
    command = [cxx, "-std=c++20", "-fsyntax-only", f"-I{course}/{edition}/include",
               f"-I{course}/common/include", "-I/usr/include/eigen3", str(path)]
    result = subprocess.run(command, capture_output=True, text=True)
    first_error = next((line for line in result.stderr.splitlines() if "error" in line), "")
    return result.returncode == 0, first_error


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--course", default=str(ROOT / "tools/grader/course"))
    parser.add_argument("--cxx", default="g++")
    parser.add_argument("cases", nargs="*")
    args = parser.parse_args()
    cases = [Path(c).resolve() for c in args.cases] or sorted(
        p.parent for p in HERE.glob("20*/*/expected.json"))
    jobs = []
    with tempfile.TemporaryDirectory() as scratch:
        for case in cases:
            directory, expected = materialise(case, Path(scratch))
            files = find_files(directory)
            if sorted(files) != sorted(FILES):
                print(f"{case.relative_to(HERE)}: missing {set(FILES) - set(files)}", file=sys.stderr)
                jobs.append(None)
                continue
            for name, path in files.items():
                must_compile = name not in expected.get("compile_errors", [])
                jobs.append((case, name, path, expected["edition"], must_compile))
        with ThreadPoolExecutor(max_workers=2) as pool:
            results = list(pool.map(
                lambda job: None if job is None else compiles(args.cxx, args.course, job[3], job[2]),
                jobs))
    failures = 0
    for job, result in zip(jobs, results):
        if job is None:
            failures += 1
            continue
        case, name, _, _, must_compile = job
        ok, first_error = result
        if ok != must_compile:
            failures += 1
            what = first_error if must_compile else "compiles, but expected.json lists a compile error"
            print(f"{case.relative_to(HERE)}/{name}: {what}", file=sys.stderr)
    checked = len([j for j in jobs if j])
    print(f"check_corpus: {len(cases)} cases, {checked} files, {failures} unexpected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
