"""The charts behind `clothref plot` (matplotlib, Agg backend).

python3 -m clothref.plot trace A.jsonl [B.jsonl] [--times 0 0.5 1] [--labels ref student] -o PREFIX
    PREFIX-cloth.EXT: the cloth (wireframe) and spheres at the recorded steps nearest each time,
    one panel per time, equal axes, y up; a second trace is overlaid in a second colour.
    PREFIX-energy.EXT: kinetic, spring, gravitational and total energy against time.
python3 -m clothref.plot sweep SWEEP.json -o PREFIX [--norm final|rms]
    PREFIX-<scene>.EXT: log-log work-precision charts from `clothref sweep` (error against
    time per simulated second, and against derivative evaluations), float and double, one curve
    per method, reference slopes for orders 1, 2 and 4, unstable points marked at the top;
    Boost.Odeint's points (`clothref sweep --peer`) as open squares in their counterpart's colour.
python3 -m clothref.plot stability STABILITY.json -o PREFIX
    PREFIX.EXT: measured and predicted stability limits per method and scene (log scale).
--formats png,svg (default) picks the files written. Every file is written to a temporary name
and renamed, so a failure leaves no partial chart. Bad input: one line on stderr, exit 2.
"""
import argparse
import json
import math
import os
import sys
import tempfile

import numpy as np

from clothref.energy import EnergyModel
from clothref.trace import TraceError, iter_steps


class _LazyPyplot:
    """matplotlib.pyplot, imported on first use: bad input is reported before the slow import."""

    def __getattr__(self, name):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as pyplot

        # SVG output without a date and with fixed ids, so a re-run writes the same file
        pyplot.rcParams["svg.hashsalt"] = "clothref"
        globals()["plt"] = pyplot
        return getattr(pyplot, name)


plt = _LazyPyplot()
METHOD_COLOURS = {"explicit": "#d62728", "implicit": "#ff7f0e", "midpoint": "#2ca02c",
                  "rk4": "#1f77b4", "symplectic": "#9467bd", "backward-euler": "#8c564b"}
# Boost.Odeint's steppers (`clothref sweep --peer`): points without a line, in the colour of the
# library's method that makes the same step
PEER_COUNTERPARTS = {"odeint-euler": "explicit", "odeint-rk4": "rk4",
                     "odeint-symplectic-euler": "symplectic"}
TRACE_COLOURS = ["#1f4e9c", "#d1495b"]


class InputProblem(Exception):
    pass


def save(figure, prefix, suffix, formats):
    written = []
    for fmt in formats:
        path = f"{prefix}{suffix}.{fmt}"
        directory = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(directory):
            raise InputProblem(f"{path}: directory {directory} does not exist")
        handle, temporary = tempfile.mkstemp(prefix=".plot-", suffix="." + fmt, dir=directory)
        os.close(handle)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)  # mkstemp's 0600 is not what a chart needs
        try:
            metadata = {"Date": None} if fmt == "svg" else {"Software": "clothref"}
            figure.savefig(temporary, format=fmt, dpi=110, metadata=metadata)
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise
        written.append(path)
    plt.close(figure)
    return written


def build_caption(header):
    build = header.get("build", {})
    return (f"{header['scene']['name']}, {header['integrator']}, {header['precision']}, "
            f"dt = {header['dt']:g} s; built by {build.get('compiler', '?')} "
            f"({build.get('build_type', '?')}, {build.get('system', '?')})")


# ---------------------------------------------------------------------------------- traces

def recorded_steps(header):
    steps, stride = int(header["steps"]), int(header["stride"])
    return sorted(set(range(0, steps + 1, stride)) | {steps})


def nearest_steps(header, times):
    recorded = np.array(recorded_steps(header))
    dt = float(header["dt"])
    return [int(recorded[np.argmin(np.abs(recorded * dt - t))]) for t in times]


def read_for_plot(path, wanted_steps):
    """Energies at every recorded step and the states at `wanted_steps`."""
    lines = iter_steps(path)
    header = next(lines)
    model = None
    times, energies, states = [], [], {}
    for step, t, bodies in lines:
        if model is None:
            x0 = bodies["cloth"]["position"] if "cloth" in bodies else None
            model = EnergyModel(header["scene"], x0)
        times.append(t)
        energies.append(model.energies(bodies))
        if step in wanted_steps:
            states[step] = (t, bodies)
    return header, np.array(times), energies, states


def largest_differences(path_a, path_b):
    """(t, largest distance between a particle's positions in the two traces) at every step both
    traces recorded; infinite where one is non-finite and the other not."""
    a, b = iter_steps(path_a), iter_steps(path_b)
    next(a)
    next(b)
    times, largest = [], []
    other = next(b, None)
    for step, t, bodies in a:
        while other is not None and other[0] < step:
            other = next(b, None)
        if other is None:
            break
        if other[0] != step:
            continue
        worst = 0.0
        for name, arrays in bodies.items():
            d = arrays["position"] - other[2][name]["position"]
            same = (arrays["position"] == other[2][name]["position"]) | (
                np.isnan(arrays["position"]) & np.isnan(other[2][name]["position"]))
            d = np.where(same, 0.0, d)
            with np.errstate(invalid="ignore", over="ignore"):
                distance = np.sqrt((d * d).sum(axis=1))
            distance = np.where(np.isnan(distance), np.inf, distance)
            worst = max(worst, float(distance.max()) if len(distance) else 0.0)
        times.append(t)
        largest.append(worst)
    return np.array(times), np.array(largest)


def sphere_mesh(center, radius, resolution=16):
    u = np.linspace(0, 2 * np.pi, resolution)
    v = np.linspace(0, np.pi, resolution // 2)
    x = center[0] + radius * np.outer(np.cos(u), np.sin(v))
    y = center[1] + radius * np.outer(np.ones_like(u), np.cos(v))
    z = center[2] + radius * np.outer(np.sin(u), np.sin(v))
    return x, y, z


def draw_state(axis, scene, bodies, colour, label):
    """Course axes (x, y up, z) drawn as matplotlib (x, z, y) so that y is up."""
    cloth = scene.get("cloth")
    if cloth is not None and "cloth" in bodies:
        x = bodies["cloth"]["position"]
        if cloth.get("grid"):
            n = int(cloth["grid"]["particles_per_edge"])
            grid = x.reshape(n, n, 3)
            axis.plot_wireframe(grid[:, :, 0], grid[:, :, 2], grid[:, :, 1], color=colour,
                                linewidth=0.5, label=label)
        else:
            axis.scatter(x[:, 0], x[:, 2], x[:, 1], color=colour, s=8, label=label)
            label = None
    if scene.get("spheres") and "spheres" in bodies:
        for center, item in zip(bodies["spheres"]["position"], scene["spheres"]["items"]):
            sx, sy, sz = sphere_mesh(center, float(item["radius"]))
            axis.plot_surface(sx, sz, sy, color=colour, alpha=0.25, linewidth=0)


def equal_axes(axis, points):
    points = points[np.all(np.isfinite(points), axis=1)]
    if len(points) == 0:
        return
    low, high = points.min(axis=0), points.max(axis=0)
    middle, half = (low + high) / 2, max(float((high - low).max()) / 2, 1e-3)
    axis.set_xlim(middle[0] - half, middle[0] + half)
    axis.set_ylim(middle[2] - half, middle[2] + half)
    axis.set_zlim(middle[1] - half, middle[1] + half)
    # zoomed out a little so the vertical axis label is not clipped
    axis.set_box_aspect((1, 1, 1), zoom=0.82)


def plot_traces(args):
    if len(args.traces) > 2:
        raise InputProblem("plot: at most two traces (a reference and a student)")
    labels = args.labels or [os.path.basename(p) for p in args.traces]
    if len(labels) != len(args.traces):
        raise InputProblem("--labels: give one label per trace")
    runs = []
    for path in args.traces:
        header = next(iter_steps(path))
        wanted = nearest_steps(header, args.times)
        runs.append((path, wanted) + read_for_plot(path, set(wanted)))
    written = []

    panels = len(args.times) + (1 if len(runs) > 1 else 0)
    figure = plt.figure(figsize=(4.2 * panels, 4.6))
    cloth_axes, points = [], []
    for k, t_wanted in enumerate(args.times):
        axis = figure.add_subplot(1, panels, k + 1, projection="3d")
        cloth_axes.append(axis)
        titles = []
        for r, (path, wanted, header, _, _, states) in enumerate(runs):
            t, bodies = states[wanted[k]]
            scene = header["scene"]
            draw_state(axis, scene, bodies, TRACE_COLOURS[r], labels[r] if k == 0 else None)
            for name, arrays in bodies.items():
                x = arrays["position"]
                if name == "spheres":
                    radii = np.array([float(i["radius"]) for i in scene["spheres"]["items"]])
                    x = np.vstack([x + radii[:, None], x - radii[:, None]])
                points.append(x)
            titles.append(f"t = {t:.3g} s (step {wanted[k]})")
        axis.view_init(elev=22, azim=-60)
        axis.set_xlabel("x (m)")
        axis.set_ylabel("z (m)")
        axis.set_zlabel("y (m), up")
        axis.tick_params(labelsize=7)
        axis.set_title(titles[0] if len(set(titles)) == 1 else "\n".join(titles), fontsize=10)
    # one scale for every panel, so sizes and sags compare across times
    for axis in cloth_axes:
        equal_axes(axis, np.vstack(points))
    if len(runs) > 1:
        # near-identical runs look the same in 3-D: the difference says how far apart they are
        axis = figure.add_subplot(1, panels, panels)
        t, largest = largest_differences(args.traces[0], args.traces[1])
        shown = np.where(largest > 0, largest, np.nan)
        axis.semilogy(t, shown, color="black", linewidth=1.2)
        zero = largest == 0
        if zero.any():
            axis.plot(t[zero], np.full(zero.sum(), np.nanmin(shown) if np.isfinite(shown).any()
                                       else 1.0), "o", markersize=3, color="gray",
                      label="identical")
            axis.legend(fontsize=8, loc="lower right")
        axis.set_xlabel("t (s)")
        axis.set_ylabel("largest position difference (m)")
        axis.set_title(f"{labels[1]} vs {labels[0]}", fontsize=10)
        axis.grid(True, which="major", alpha=0.3)
        handles, names = cloth_axes[0].get_legend_handles_labels()
        figure.legend(handles, names, loc="upper left", fontsize=9)
    figure.text(0.01, 0.01, " | ".join(build_caption(r[2]) for r in runs), fontsize=7)
    figure.tight_layout(rect=(0, 0.04, 1, 1))
    written += save(figure, args.output, "-cloth", args.formats)

    figure, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex=True)
    kinds = [("kinetic", "kinetic"), ("spring", "spring potential"),
             ("gravitational", "gravitational potential (0 at y = 0)"), ("total", "total")]
    for axis, (key, title) in zip(axes.flat, kinds):
        for r, (path, wanted, header, times, energies, _) in enumerate(runs):
            axis.plot(times, [e[key] for e in energies], color=TRACE_COLOURS[r],
                      linestyle="-" if r == 0 else "--", label=labels[r])
        axis.set_title(title, fontsize=10)
        axis.set_ylabel("energy (J)")
        axis.grid(True, alpha=0.3)
    for axis in axes[1]:
        axis.set_xlabel("time (s)")
    axes[0][0].legend(fontsize=9)
    figure.text(0.01, 0.01, " | ".join(build_caption(r[2]) for r in runs), fontsize=7)
    figure.tight_layout(rect=(0, 0.03, 1, 1))
    written += save(figure, args.output, "-energy", args.formats)
    return written


# ---------------------------------------------------------------------------------- sweeps

def read_json(path, expected_key):
    try:
        with open(path, encoding="utf-8") as handle:
            data = json.load(handle)
    except OSError as error:
        raise InputProblem(f"{path}: cannot open ({error.strerror})") from None
    except json.JSONDecodeError as error:
        raise InputProblem(f"{path}:{error.lineno}: not JSON ({error.msg})") from None
    if not isinstance(data, dict) or expected_key not in data:
        raise InputProblem(f"{path}: no '{expected_key}' key (is this the right file?)")
    return data


def slope_fan(axis, x_left, y_top, orders=(1, 2, 4)):
    """Reference slopes: from (x_left, y_top), one decade of work, error ~ work^-p."""
    for p, style in zip(orders, [":", "-.", "--"]):
        xs = np.array([x_left, x_left * 10])
        ys = y_top * (xs / x_left) ** (-p)
        axis.plot(xs, ys, color="black", linestyle=style, linewidth=1.0, label=f"order {p}")
        axis.text(xs[1] * 1.1, ys[1], f"{p}", fontsize=8, va="center", clip_on=True)


def plot_sweep(args):
    data = read_json(args.input, "points")
    key = "error_final" if args.norm == "final" else "error_rms"
    scenes = list(dict.fromkeys(p["scene"] for p in data["points"]))
    written = []
    for scene in scenes:
        points = [p for p in data["points"] if p["scene"] == scene]
        precisions = list(dict.fromkeys(p["precision"] for p in points))
        figure, axes = plt.subplots(len(precisions), 2, figsize=(13.5, 4.8 * len(precisions)),
                                    squeeze=False)
        finite_all = [p[key] for p in points if p[key] is not None and p[key] > 0]
        if not finite_all:
            raise InputProblem(f"{args.input}: scene {scene} has no finite error to plot")
        top = max(finite_all) * 10
        bottom = min(finite_all) / 3
        for row, precision in enumerate(precisions):
            subset = [p for p in points if p["precision"] == precision]
            timing = ("cpu_seconds_median", "CPU time per simulated second (s), median of runs")
            if any("cpu_seconds_median" not in p for p in subset):
                timing = ("seconds_median", "wall time per simulated second (s), median of runs")
            for col, (work, label) in enumerate([
                    timing, ("evaluations", "derivative evaluations to the horizon")]):
                axis = axes[row][col]
                for method in dict.fromkeys(p["method"] for p in subset):
                    mine = [p for p in subset if p["method"] == method]
                    peer = method in PEER_COUNTERPARTS
                    colour = METHOD_COLOURS.get(PEER_COUNTERPARTS.get(method, method), "black")
                    good = sorted([p for p in mine if p["stable"] and p[key] is not None],
                                  key=lambda p: p[work])
                    if good and peer:
                        axis.plot([p[work] for p in good], [p[key] for p in good], marker="s",
                                  markersize=8, markerfacecolor="none", markeredgewidth=1.2,
                                  linestyle="none", color=colour,
                                  label=f"{method} (Boost.Odeint)")
                    elif good:
                        axis.plot([p[work] for p in good], [p[key] for p in good], marker="o",
                                  markersize=3.5, color=colour, label=method)
                    # unstable points are kept: at their error if the run stayed finite,
                    # otherwise on the line at the top
                    bad = [p for p in mine if not p["stable"]]
                    if bad:
                        axis.scatter([p[work] for p in bad],
                                     [p[key] if p[key] is not None else top for p in bad],
                                     marker="x", color=colour, s=36, linewidths=1.5, zorder=3)
                xs = [p[work] for p in subset if p[work] and p[work] > 0]
                slope_fan(axis, min(xs) * 1.5, top / 20)
                axis.axhline(top, color="black", linewidth=0.5)
                axis.text(0.99, 0.985, "x: unstable (on the top line: blew up)",
                          transform=axis.transAxes, fontsize=8, va="top", ha="right")
                if precision == "float" and bottom < 2.0 ** -24:
                    floor = 2.0 ** -24
                    axis.axhline(floor, color="black", linestyle=(0, (1, 3)), linewidth=0.8)
                    axis.text(0.99, floor * 1.4, "float epsilon x 1 m", ha="right",
                              transform=axis.get_yaxis_transform(), fontsize=8)
                axis.set_xscale("log")
                axis.set_yscale("log")
                axis.set_ylim(bottom, top * 3)
                axis.set_xlabel(label)
                axis.set_ylabel(f"position error, {args.norm} (m)")
                axis.set_title(f"{scene}, {precision}", fontsize=10)
                axis.grid(True, which="major", alpha=0.3)
            # outside the axes: inside, the legend covered the order slopes
            axes[row][1].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                                borderaxespad=0)
        caption = (f"{data.get('machine', '?')}; {data.get('compiler', '?')} "
                   f"({data.get('build_type', '?')}). Error: {data['norms'][key]}. "
                   "\nTimes: the thread's CPU time (wall time, min and max are in the data); on a "
                   "shared 2-core machine they are noisy, evaluation counts are not.")
        figure.text(0.01, 0.005, caption, fontsize=7)
        figure.tight_layout(rect=(0, 0.035, 0.87, 1))  # the legend sits to the right
        written += save(figure, args.output, f"-{scene}", args.formats)
    return written


def plot_stability(args):
    from matplotlib.patches import Patch

    data = read_json(args.input, "results")
    results = data["results"]
    scenes = list(dict.fromkeys(r["scene"] for r in results))
    figure, axes = plt.subplots(1, len(scenes), figsize=(5.6 * len(scenes), 4.8), squeeze=False)
    series = [("theory (amplification on the linear modes)", None, "#888888"),
              ("measured, float", "float", "#1f77b4"), ("measured, double", "double", "#ff7f0e")]
    width = 0.26
    for axis, scene in zip(axes[0], scenes):
        rows = [r for r in results if r["scene"] == scene]
        methods = list(dict.fromkeys(r["method"] for r in rows))
        values = [v for r in rows for v in (r["dt_max_measured"], r["dt_max_theory"],
                                             r["search_low"]) if v]
        floor = min(values) / 2
        for s, (label, precision, colour) in enumerate(series):
            for m, method in enumerate(methods):
                match = [r for r in rows if r["method"] == method and
                         (precision is None or r["precision"] == precision)]
                if not match:
                    continue
                r = match[0]
                value = r["dt_max_theory"] if precision is None else r["dt_max_measured"]
                note = r["theory_note"] if precision is None else r["measured_note"]
                x = m + (s - 1) * width
                if value is not None:
                    axis.bar(x, value - floor, bottom=floor, width=width, color=colour)
                elif precision is not None and note.startswith("stable at every dt"):
                    # stable up to the end of the search: a hatched bar to that end
                    axis.bar(x, r["search_high"] - floor, bottom=floor, width=width,
                             color="white", edgecolor=colour, hatch="///")
                    axis.text(x, r["search_high"], "\u2265", ha="center", va="bottom",
                              fontsize=9, color=colour)
                else:
                    text = "no limit" if "never exceeds" in note else "none"
                    axis.text(x, floor * 1.08, text, rotation=90, ha="center", va="bottom",
                              fontsize=8, color=colour, fontweight="bold")
        axis.set_yscale("log")
        axis.set_xticks(range(len(methods)))
        axis.set_xticklabels(methods, rotation=25, ha="right", fontsize=9)
        axis.set_xlim(-0.6, len(methods) - 0.4)
        axis.set_ylabel("largest stable dt (s)")
        axis.set_title(scene, fontsize=10)
        axis.grid(True, axis="y", which="both", alpha=0.3)
    handles = [Patch(color=colour, label=label) for label, _, colour in series]
    handles.append(Patch(facecolor="white", edgecolor="black", hatch="///",
                         label="stable at every dt tried (up to the search's end)"))
    figure.legend(handles=handles, loc="upper center", ncol=4, fontsize=8)
    figure.text(0.01, 0.01, "none: unstable at every dt (theory) or already at the smallest dt "
                "tried (measured); no limit: the spectral radius never exceeds 1. Criteria and "
                "search ranges: docs/methods.md", fontsize=7)
    figure.tight_layout(rect=(0, 0.04, 1, 0.92))
    return save(figure, args.output, "", args.formats)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="clothref plot", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    trace = commands.add_parser("trace")
    trace.add_argument("traces", nargs="+")
    trace.add_argument("--times", type=float, nargs="+", default=[0.0, 0.5, 1.0])
    trace.add_argument("--labels", nargs="+")
    for sub in (commands.add_parser("sweep"), commands.add_parser("stability")):
        sub.add_argument("input")
        if sub.prog.endswith("sweep"):
            sub.add_argument("--norm", choices=["final", "rms"], default="final")
    for sub in commands.choices.values():
        sub.add_argument("-o", "--output", required=True, help="output prefix")
        sub.add_argument("--formats", default="png,svg", help="comma-separated: png, svg, pdf")
    args = parser.parse_args(argv)
    args.formats = [f for f in args.formats.split(",") if f]
    for f in args.formats:
        if f not in ("png", "svg", "pdf"):
            print(f"clothref plot: --formats: unknown format '{f}' (png, svg, pdf)",
                  file=sys.stderr)
            return 2
    try:
        run = {"trace": plot_traces, "sweep": plot_sweep, "stability": plot_stability}
        for path in run[args.command](args):
            print(path)
    except (InputProblem, TraceError) as error:
        print(f"clothref plot: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
