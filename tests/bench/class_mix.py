#!/usr/bin/env python3
"""What a class costs to grade (docs/performance.md, "Grading a class"): a mix of submissions in
the proportions of a real class, graded as one batch at --jobs 2 with an empty object cache, and
each one alone, measuring busy CPU (the grader and every process it waited for: getrusage of the
children, which load disturbs less than wall) and wall.

The mix (38 submissions, every file made distinct by a comment so no two share an object, as in a
real class): 8 correct, 20 real-shaped failing ones (tests/grader/corpus, tests/grader/handwritten),
5 crashes (about one in eight), a compile error, a link error, an endless loop, undefined
behaviour (two runs that differ) and NaN (tests/grader/submissions, tests/grader/adversarial).

Prints, per kind of submission, busy CPU and wall of one graded alone (medians and sums), then the
batch's wall and busy CPU, the busy CPU per submission, and the time 300 such submissions take at
--jobs 2 on 2 cores (busy CPU / 2, the batch bound by CPU; and the batch's wall scaled, which only
means something on a quiet machine). The load average and CPU pressure around each part are printed
with the figures.

Usage: tests/bench/class_mix.py [--build BUILD_DIR] [--parts alone,batch] [--keep DIR]
A benchmark, not a test: nothing is asserted but that every submission got a row.
"""
import argparse
import csv
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GRADER = os.path.join(ROOT, "tests", "grader")

# (kind, folder under tests/grader, copies): copies of one folder differ by their comment.
MIX = [
    ("correct", "submissions/2022/reference", 3),
    ("correct", "submissions/2024/reference", 3),
    ("correct", "submissions/2022/accepted-variants", 1),
    ("correct", "submissions/2024/accepted-variants", 1),
    ("failing", "corpus/2022/big5-k4x-hooke-sign-symplectic-predictor", 1),
    ("failing", "corpus/2022/dt-halved-per-body-rk4-mass-formula", 1),
    ("failing", "corpus/2022/float-half-sixth-position-full-velocity", 1),
    ("failing", "corpus/2022/ref-backup-discarded-stages-one-end", 1),
    ("failing", "corpus/2022/symplectic-both-sqrt2-normal-stage-current", 1),
    ("failing", "corpus/2024/big5-shear-full-velocity-integer-half-per-body", 1),
    ("failing", "corpus/2024/course-cloth-pins-bend-correction", 1),
    ("failing", "corpus/2024/swapped-damper-sign-per-body-midpoint", 1),
    ("failing", "handwritten/2022/chang", 1),
    ("failing", "handwritten/2022/cheng", 1),
    ("failing", "handwritten/2022/hsu", 1),
    ("failing", "handwritten/2022/huang", 1),
    ("failing", "handwritten/2022/kuo", 1),
    ("failing", "handwritten/2022/lin-big5", 1),
    ("failing", "handwritten/2024/chiu", 1),
    ("failing", "handwritten/2024/ho", 1),
    ("failing", "handwritten/2024/hsieh", 1),
    ("failing", "handwritten/2024/kao", 1),
    ("failing", "handwritten/2024/lee", 1),
    ("failing", "handwritten/2024/tang", 1),
    ("crash", "corpus/2024/dangling-auto-sixth-touching", 1),
    ("crash", "handwritten/2022/wu", 1),
    ("crash", "handwritten/2024/sun", 1),
    ("crash", "submissions/2022/force-dangling-auto", 1),
    ("crash", "adversarial/segfault", 1),
    ("compile-error", "adversarial/compile-error", 1),
    ("compile-error", "adversarial/link-error", 1),
    ("endless-loop", "adversarial/infinite-loop", 1),
    ("undefined-behaviour", "submissions/2022/midpoint-ref-backup", 1),
    ("nan", "adversarial/nan-results", 1),
]
KINDS = ["correct", "failing", "crash", "compile-error", "endless-loop", "undefined-behaviour",
         "nan"]


def lay_out(out):
    """The mix in OUT/NN-kind-name/ (a folder's `base` first, then its own files over it)."""
    entries = []
    n = 0
    for kind, folder, copies in MIX:
        source = os.path.join(GRADER, folder)
        base = ""
        expected = os.path.join(source, "expected.json")
        if os.path.exists(expected):
            base = json.load(open(expected)).get("base", "")
        for _ in range(copies):
            n += 1
            name = f"{n:02d}-{kind}-{os.path.basename(folder)}"
            target = os.path.join(out, name)
            os.makedirs(target)
            for origin in ([os.path.join(GRADER, "submissions", base)] if base else []) + [source]:
                for dirpath, _, files in os.walk(origin):
                    for f in files:
                        if f.endswith(".cpp"):
                            shutil.copy(os.path.join(dirpath, f), os.path.join(target, f))
            for f in os.listdir(target):  # distinct files: no object is shared between two
                with open(os.path.join(target, f), "ab") as handle:
                    handle.write(f"\n// class-mix submission {n} ({folder})\n\n".encode())
            entries.append((kind, name))
    return entries


def load():
    with open("/proc/loadavg") as f:
        text = "load " + " ".join(f.read().split()[:3])
    try:
        with open("/proc/pressure/cpu") as f:
            some = f.readline().split()
            text += ", CPU pressure " + some[1].replace("avg10=", "") + " %"
    except OSError:
        pass
    return text


class BusyCpu:
    """Busy CPU of a command and everything it starts: a cgroup of its own where this machine
    allows one (cgroup v1 cpuacct, or v2 cpu.stat; the grader's own cgroups for its runs nest
    inside it), else getrusage of the children (which misses what a sandbox's init reaps)."""

    def __init__(self):
        self.path, self.read = None, None
        name = f"clothref-bench-{os.getpid()}"
        v1 = "/sys/fs/cgroup/cpuacct"
        try:
            if os.path.exists(os.path.join(v1, "cpuacct.usage")):
                self.path = os.path.join(v1, name)
                os.mkdir(self.path)
                self.read = lambda: int(open(os.path.join(self.path, "cpuacct.usage")).read()) / 1e9
            else:
                own = [line.split("::", 1)[1].strip() for line in open("/proc/self/cgroup")
                       if line.startswith("0::")][0]
                self.path = os.path.join("/sys/fs/cgroup" + own, name)
                os.mkdir(self.path)
                self.read = lambda: int(next(
                    line.split()[1] for line in open(os.path.join(self.path, "cpu.stat"))
                    if line.startswith("usage_usec"))) / 1e6
        except (OSError, IndexError):
            self.path, self.read = None, None
        self.how = ("cgroup " + self.path) if self.path else "getrusage of the children"

    def join(self):
        """In the child before exec: into the cgroup."""
        if self.path:
            with open(os.path.join(self.path, "cgroup.procs"), "w") as f:
                f.write("0")

    def close(self):
        if self.path:
            try:
                os.rmdir(self.path)
            except OSError:
                pass


CPU = None


def run(command, **kwargs):
    """Runs `command`; returns (exit code, wall s, busy CPU s of it and everything it started)."""
    before = CPU.read() if CPU.read else 0
    start = time.monotonic()
    process = subprocess.Popen(command, preexec_fn=CPU.join, **kwargs)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    busy = CPU.read() - before if CPU.read else usage.ru_utime + usage.ru_stime
    return os.waitstatus_to_exitcode(status), wall, busy


def summary(values):
    return f"median {statistics.median(values):6.2f}, sum {sum(values):7.1f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--parts", default="alone,batch")
    parser.add_argument("--keep", help="keep the submissions and outputs in this folder")
    args = parser.parse_args()
    clothref = os.path.join(os.path.abspath(args.build), "bin", "clothref")
    if not os.access(clothref, os.X_OK):
        sys.exit(f"class_mix: {clothref} not built")
    parts = args.parts.split(",")
    work = tempfile.mkdtemp(prefix="clothref-class-mix-")
    global CPU
    CPU = BusyCpu()
    print(f"busy CPU measured by {CPU.how}")
    try:
        entries = lay_out(os.path.join(work, "subs"))
        count = len(entries)
        counts = {k: sum(1 for kind, _ in entries if kind == k) for k in KINDS}
        print(f"class mix: {count} submissions: " +
              ", ".join(f"{counts[k]} {k}" for k in KINDS if counts[k]))
        kind_of = dict((name, kind) for kind, name in entries)

        if "alone" in parts:
            # Each alone, one after the other, sharing one object cache as a batch does.
            print(f"alone, before: {load()}")
            cache = os.path.join(work, "alone-cache")
            cpu, wall, verdicts = {}, {}, {}
            for kind, name in entries:
                results = os.path.join(work, "alone", name + ".json")
                os.makedirs(os.path.dirname(results), exist_ok=True)
                code, seconds, busy = run(
                    [clothref, "grade", os.path.join(work, "subs", name), "--cache-dir", cache,
                     "--results", results], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                verdict = "not-gradable"
                if code == 0:
                    verdict = json.load(open(results)).get("extra_data", {}).get("verdict", "?")
                cpu.setdefault(kind, []).append(busy)
                wall.setdefault(kind, []).append(seconds)
                verdicts[name] = verdict
                print(f"  {name:58s} {verdict:14s} busy CPU {busy:6.2f} s, wall {seconds:6.2f} s",
                      flush=True)
            print(f"alone, after: {load()}")
            print("per kind, graded alone (s):")
            for k in KINDS:
                if k in cpu:
                    print(f"  {k:20s} n={len(cpu[k]):2d}  busy CPU {summary(cpu[k])}   "
                          f"wall {summary(wall[k])}")
            total = sum(sum(v) for v in cpu.values())
            print(f"  all                  n={count:2d}  busy CPU {total / count:6.2f} s per "
                  f"submission; 300 at --jobs 2 on 2 cores: {total / count * 300 / 2 / 60:.1f} "
                  f"min of busy CPU")
            correct = statistics.median(cpu.get("correct", [0])) or 1
            worst = max((statistics.median(v), k) for k, v in cpu.items() if k != "endless-loop")
            print(f"  the costliest kind but the endless loop, against a correct one: {worst[1]} "
                  f"{worst[0] / correct:.1f}x (medians)")

        if "batch" in parts:
            print(f"batch, before: {load()}")
            out = os.path.join(work, "batch")
            log = os.path.join(work, "batch.log")
            with open(log, "w") as handle:
                code, seconds, busy = run(
                    [clothref, "grade"] + [os.path.join(work, "subs", n) for _, n in entries] +
                    ["--out", out, "--jobs", "2"], stderr=handle)
            closing = open(log).read().splitlines()
            slowest = [k for k, line in enumerate(closing) if "the slowest" in line]
            for line in closing[slowest[0]:] if slowest else []:  # the batch's own account
                print("  " + line)
            print(f"batch, after: {load()}")
            rows = list(csv.DictReader(open(os.path.join(out, "grades.csv"))))
            if code != 0 or len(rows) != count:
                sys.exit(f"class_mix: the batch exited {code} with {len(rows)} rows of {count}")
            per_kind = {}
            for row in rows:
                per_kind.setdefault(kind_of[row["submission"]], []).append(float(row["seconds"]))
            print(f"batch of {count} at --jobs 2, empty cache: wall {seconds:.1f} s, busy CPU "
                  f"{busy:.1f} s ({busy / count:.2f} s per submission)")
            print("  wall per submission in the batch, per kind (s): " + "; ".join(
                f"{k} {statistics.median(per_kind[k]):.1f}" for k in KINDS if k in per_kind))
            print(f"  300 at --jobs 2 on 2 cores: {busy / count * 300 / 2 / 60:.1f} min (busy "
                  f"CPU / 2 cores); {seconds / count * 300 / 60:.1f} min (this wall, scaled)")
            if args.keep:
                shutil.copytree(out, os.path.join(args.keep, "batch"), dirs_exist_ok=True)
    finally:
        CPU.close()
        if args.keep:
            shutil.copytree(os.path.join(work, "subs"), os.path.join(args.keep, "subs"),
                            dirs_exist_ok=True)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
