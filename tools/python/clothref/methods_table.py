"""The table of docs/methods.md, computed from `clothref sweep` and `clothref stability` output.

python3 -m clothref.methods_table SWEEP.json STABILITY.json [--target 1e-3] [--precision float]

Columns (one row per method):
  observed order   least-squares slope of log(error_final) on log(dt), spring scene, double,
                   stable points with dt <= 0.01 s and error above 1e-11 m (the double floor)
  evals/step       derivative evaluations per step (evaluations / steps)
  us/step          course2022 at dt = 1e-4 s: median CPU time per simulated second x dt
  dt_max           course2022, theory and measured (clothref stability), in the chosen precision
  cost at target   course2022: the cheapest stable point (fewest evaluations) whose position
                   error at t = 1 s is <= target: its dt and wall seconds per simulated second
Also prints, per precision and error level (1e-2, 1e-4, 1e-6, both scenes), the method that
reaches it with the fewest evaluations.
"""
import argparse
import json
import math
import sys


def fit_order(points):
    xs = [math.log(p["dt"]) for p in points]
    ys = [math.log(p["error_final"]) for p in points]
    n = len(xs)
    if n < 2:
        return None
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def secs(point):
    """CPU seconds per simulated second when the sweep has them, else wall seconds."""
    return point.get("cpu_seconds_median", point["seconds_median"])


def fmt(value, spec=".3g"):
    return "-" if value is None else format(value, spec)


PEERS = ("odeint-euler", "odeint-rk4", "odeint-symplectic-euler")


def cheapest(points, target):
    ok = [p for p in points if p["stable"] and p["error_final"] is not None
          and p["error_final"] <= target]
    return min(ok, key=lambda p: (p["evaluations"], secs(p))) if ok else None


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sweep")
    parser.add_argument("stability")
    parser.add_argument("--target", type=float, default=1e-3)
    parser.add_argument("--precision", default="float")
    args = parser.parse_args(argv)
    with open(args.sweep, encoding="utf-8") as handle:
        sweep = json.load(handle)["points"]
    with open(args.stability, encoding="utf-8") as handle:
        stability = json.load(handle)["results"]
    # the library's methods only: the odeint peer's points (`sweep --peer`) sit on their
    # counterparts' and are charted beside them, not tabled
    sweep = [p for p in sweep if p["method"] not in PEERS]
    methods = list(dict.fromkeys(p["method"] for p in sweep))

    print(f"| method | observed order | evals/step | us/step (course2022, {args.precision}, "
          f"dt 1e-4) | dt_max theory (s) | dt_max measured (s) | to reach {args.target:g} m "
          f"at t = 1 s on course2022 ({args.precision}) |")
    print("|---|---|---|---|---|---|---|")
    for method in methods:
        spring = [p for p in sweep if p["scene"] == "spring" and p["method"] == method
                  and p["precision"] == "double" and p["stable"] and p["dt"] <= 0.01
                  and p["error_final"] is not None and p["error_final"] > 1e-11]
        order = fit_order(spring)
        course = [p for p in sweep if p["scene"] == "course2022" and p["method"] == method
                  and p["precision"] == args.precision]
        evals = course[0]["evaluations"] / course[0]["steps"] if course else None
        at = [p for p in course if abs(p["dt"] - 1e-4) < 1e-12]
        us = secs(at[0]) * at[0]["dt"] * 1e6 if at else None
        limit = [r for r in stability if r["scene"] == "course2022" and r["method"] == method
                 and r["precision"] == args.precision]
        theory = limit[0]["dt_max_theory"] if limit else None
        measured = limit[0]["dt_max_measured"] if limit else None
        if limit and theory is None and "every dt > 0" in limit[0]["theory_note"]:
            theory_text = "none"
        elif limit and theory is None:
            theory_text = "no limit"
        else:
            theory_text = fmt(theory, ".4g")
        if limit and measured is None and "stable at every dt" in limit[0]["measured_note"]:
            measured_text = f">= {limit[0]['search_high']:g}"
        else:
            measured_text = fmt(measured, ".4g")
        best = cheapest(course, args.target)
        if best:
            reach = (f"dt {best['dt']:.3g} s: {best['evaluations']} evaluations, "
                     f"{secs(best):.3g} CPU s per simulated s")
        else:
            finite = [p for p in course if p["stable"] and p["error_final"] is not None]
            low = min(finite, key=lambda p: p["error_final"]) if finite else None
            reach = ("not reached" + (f" (best {low['error_final']:.2g} m at dt "
                                      f"{low['dt']:.3g} s)" if low else ""))
        print(f"| {method} | {fmt(order, '.2f')} | {fmt(evals, '.0f')} | {fmt(us, '.0f')} | "
              f"{theory_text} | {measured_text} | {reach} |")

    print()
    print("| scene | precision | error <= 1e-2 m | error <= 1e-4 m | error <= 1e-6 m |")
    print("|---|---|---|---|---|")
    for scene in dict.fromkeys(p["scene"] for p in sweep):
        for precision in ("float", "double"):
            cells = []
            for target in (1e-2, 1e-4, 1e-6):
                candidates = []
                for method in methods:
                    best = cheapest([p for p in sweep if p["scene"] == scene
                                     and p["method"] == method
                                     and p["precision"] == precision], target)
                    if best:
                        candidates.append((best["evaluations"], method, best))
                if candidates:
                    evaluations, method, best = min(candidates)
                    cells.append(f"{method} (dt {best['dt']:.3g} s, {evaluations} evals, "
                                 f"{secs(best):.3g} CPU s/s)")
                else:
                    cells.append("none in the sweep")
            print(f"| {scene} | {precision} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
