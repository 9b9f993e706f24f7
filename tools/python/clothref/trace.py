"""Streaming reader of clothref traces (docs/trace-format.md).

read_trace(path, keep=None) -> Trace with
  header     the header line as a dict (scene, integrator, precision, dt, steps, stride, bodies)
  step       (S,) int64, the recorded steps kept
  t          (S,) float64, seconds
  bodies     {"cloth": {"position": (S, N, 3), "velocity": (S, N, 3)}, "spheres": {...}},
             metres and metres per second, float64 (a float trace widens exactly)
Lines are parsed one at a time, so memory holds only the steps kept. `keep` is a predicate on
(step, t); by default every recorded step is kept. Non-finite values (written as the strings
"NaN", "Infinity", "-Infinity") become float NaN / inf. Like the C++ reader, the path "-" is
standard input (read once and kept, so a trace piped in can be read twice) and gzip is
recognised by its first byte, whatever the name.
"""
import gzip
import io
import json
import math
import sys
from dataclasses import dataclass, field

import numpy as np


class TraceError(Exception):
    """A file that is not a readable clothref trace; the message names the file and line."""


_NONFINITE = {"NaN": math.nan, "Infinity": math.inf, "-Infinity": -math.inf}


def _number_array(rows, where, dtype):
    # a float trace holds the shortest text that reads back as the same float: read it as a
    # double, round to float32 (which recovers that float), then widen exactly
    try:
        return np.array([[_NONFINITE.get(v, v) if isinstance(v, str) else v for v in row]
                         for row in rows], dtype=np.float64).astype(dtype).astype(
                             np.float64).reshape(-1, 3)
    except (TypeError, ValueError) as error:
        raise TraceError(f"{where}: expected [[x, y, z], ...] numbers ({error})") from None


@dataclass
class Trace:
    header: dict
    step: np.ndarray
    t: np.ndarray
    bodies: dict = field(default_factory=dict)


_stdin_bytes = None  # standard input, once read


def _open_lines(path):
    """A text handle on the trace at `path` ("-": standard input), gzip or not."""
    global _stdin_bytes
    if path == "-":
        if _stdin_bytes is None:
            _stdin_bytes = sys.stdin.buffer.read()
        raw = io.BufferedReader(io.BytesIO(_stdin_bytes))
    else:
        try:
            raw = open(path, "rb")
        except OSError as error:
            raise TraceError(f"{path}: cannot open ({error.strerror})") from None
    # 0x1f cannot start a JSON text: it is gzip's first byte
    if raw.peek(1)[:1] == b"\x1f":
        raw = gzip.GzipFile(fileobj=raw, mode="rb")
    return io.TextIOWrapper(raw, encoding="utf-8")


def _lines(handle, path):
    """The handle's lines; a corrupt or cut gzip stream is one TraceError naming the file."""
    try:
        yield from handle
    except (OSError, EOFError, UnicodeDecodeError) as error:
        raise TraceError(f"{path}: cannot read ({error})") from None


def iter_steps(path):
    """Yields the header once, then (step, t, {body: {"position", "velocity"}}) per line."""
    handle = _open_lines(path)
    if path == "-":
        path = "standard input"
    with handle:
        lines = _lines(handle, path)
        first = next(lines, "")
        try:
            header = json.loads(first)
        except json.JSONDecodeError as error:
            raise TraceError(f"{path}:1: header: not JSON ({error.msg})") from None
        if not isinstance(header, dict) or header.get("format") != "clothref-trace":
            raise TraceError(f"{path}:1: header: /format: not a clothref trace")
        if header.get("version") != 1:
            raise TraceError(f"{path}:1: header: /version: unsupported version "
                             f"{header.get('version')} (this reader reads 1)")
        yield header
        counts = {b["name"]: int(b["particles"]) for b in header.get("bodies", [])}
        dtype = np.float32 if header.get("precision") == "float" else np.float64
        for number, line in enumerate(lines, start=2):
            if not line.strip():
                continue
            try:
                item = json.loads(line)
                step, t = int(item["step"]), float(item["t"])
                bodies = {}
                for name, count in counts.items():
                    body = item["bodies"][name]
                    where = f"{path}:{number}: /bodies/{name}"
                    position = _number_array(body["position"], where + "/position", dtype)
                    velocity = _number_array(body["velocity"], where + "/velocity", dtype)
                    if len(position) != count or len(velocity) != count:
                        raise TraceError(f"{where}: {len(position)} particles, the header "
                                         f"declares {count}")
                    bodies[name] = {"position": position, "velocity": velocity}
            except json.JSONDecodeError as error:
                raise TraceError(f"{path}:{number}: not JSON ({error.msg})") from None
            except (KeyError, TypeError) as error:
                raise TraceError(f"{path}:{number}: missing or malformed key {error}") from None
            yield step, t, bodies


def read_trace(path, keep=None):
    """Reads a trace; keeps the steps for which keep(step, t) is true (all by default)."""
    lines = iter_steps(path)
    header = next(lines)
    steps, times = [], []
    stacks = {b["name"]: {"position": [], "velocity": []} for b in header.get("bodies", [])}
    for step, t, bodies in lines:
        if keep is not None and not keep(step, t):
            continue
        steps.append(step)
        times.append(t)
        for name, arrays in bodies.items():
            stacks[name]["position"].append(arrays["position"])
            stacks[name]["velocity"].append(arrays["velocity"])
    out = {}
    for name, arrays in stacks.items():
        count = next(int(b["particles"]) for b in header["bodies"] if b["name"] == name)
        out[name] = {key: (np.stack(value) if value else np.zeros((0, count, 3)))
                     for key, value in arrays.items()}
    return Trace(header, np.array(steps, dtype=np.int64), np.array(times, dtype=np.float64), out)
