#!/usr/bin/env python3
"""Busy CPU of a command and everything it starts (the grader's benchmarks: tests/bench/class_mix.py
imports BusyCpu; tests/bench/grade_speed.sh runs this file).

A cgroup of its own where this machine allows one (cgroup v1 cpuacct, or v2 cpu.stat; the
grader's own cgroups for its runs nest inside it), else getrusage of the children (which misses
what a sandbox's init reaps). On a shared machine busy CPU is disturbed less than wall, but not
undisturbed: a CPU second costs more while the other hyperthread or the host is busy, so
busy_cpu.py also prints a yardstick, the busy CPU of a fixed piece of work run just before
(`--yardstick`: a small fixed C++ file compiled at -O2, median of three), to compare sittings by.

Usage: tests/bench/busy_cpu.py [--yardstick] [--label TEXT] COMMAND...
Prints "busy CPU <s> s, wall <s> s, load <1 5 15>" (and the yardstick's seconds) to stderr and
exits with the command's status.
"""
import os
import subprocess
import sys
import tempfile
import time


class BusyCpu:
    """A cgroup to run commands in, and its busy CPU seconds so far (`read`, None without one)."""

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

    def run(self, command, **kwargs):
        """Runs `command`: (exit code, wall s, busy CPU s of it and everything it started)."""
        before = self.read() if self.read else 0
        start = time.monotonic()
        process = subprocess.Popen(command, preexec_fn=self.join, **kwargs)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.monotonic() - start
        busy = self.read() - before if self.read else usage.ru_utime + usage.ru_stime
        return os.waitstatus_to_exitcode(status), wall, busy

    def close(self):
        if self.path:
            for _ in range(50):  # the last processes leave the cgroup as they are reaped
                try:
                    os.rmdir(self.path)
                    return
                except OSError:
                    time.sleep(0.1)


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


YARDSTICK_SOURCE = """#include <algorithm>
#include <map>
#include <string>
#include <vector>
std::map<std::string, std::vector<double>> table(const std::vector<std::string>& names) {
  std::map<std::string, std::vector<double>> out;
  for (const auto& name : names) out[name].assign(name.size(), 1.0);
  for (auto& [name, values] : out) std::sort(values.begin(), values.end());
  return out;
}
"""


def yardstick(cpu, runs=3):
    """The median busy CPU of compiling YARDSTICK_SOURCE at -O2: what a CPU second is worth now
    (the same work costs more CPU seconds while the machine is busy)."""
    with tempfile.TemporaryDirectory(prefix="clothref-yardstick-") as work:
        source, out = os.path.join(work, "yardstick.cpp"), os.path.join(work, "yardstick.o")
        with open(source, "w") as f:
            f.write(YARDSTICK_SOURCE)
        times = []
        for _ in range(runs):
            _, _, busy = cpu.run(["g++", "-std=c++20", "-O2", "-c", source, "-o", out])
            times.append(busy)
        return sorted(times)[len(times) // 2]


def main():
    args = sys.argv[1:]
    stick, label = False, ""
    while args and args[0].startswith("--"):
        if args[0] == "--yardstick":
            stick, args = True, args[1:]
        elif args[0] == "--label" and len(args) > 1:
            label, args = args[1] + ": ", args[2:]
        else:
            sys.exit(f"busy_cpu: unknown option {args[0]}")
    if not args:
        sys.exit("busy_cpu: no command given")
    cpu = BusyCpu()
    try:
        stick = yardstick(cpu) if stick else None
        code, wall, busy = cpu.run(args)
        text = f"{label}busy CPU {busy:.2f} s, wall {wall:.2f} s, {load()}"
        if stick is not None:
            text += f"; yardstick {stick:.2f} s"
        print(text, file=sys.stderr, flush=True)
    finally:
        cpu.close()
    sys.exit(code)


if __name__ == "__main__":
    main()
