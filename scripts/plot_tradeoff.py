#!/usr/bin/env python3
"""Turns the trade program's CSV (bench/tradeoff.cpp) into doc/tradeoff.md and doc/tradeoff.png.

Usage: plot_tradeoff.py CSV MARKDOWN PNG

The table lists every option's cost beside its errors; the plot shows error against cost, log-log,
one curve per integrator and model, with the Pareto front marked; the convergence order of each
integrator is the slope of log error against log step.
"""
import csv
import math
import platform
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

INTEGRATORS = ["semi_implicit_euler", "velocity_verlet", "rk4"]
MODELS = ["rolling", "smooth"]
COLOURS = {"semi_implicit_euler": "tab:red", "velocity_verlet": "tab:blue", "rk4": "tab:green"}
STYLES = {"rolling": "-", "smooth": "--"}
SUBSTEP_MARKERS = {1: "o", 4: "^", 16: "s"}
CLOSED_FORMS = ["incline", "bounce", "slip_to_roll", "rolling_resistance", "drag", "turning_board"]
FLOOR = 1e-16  # errors at rounding are drawn here on the log axes
ROUNDING = 1e-12  # relative errors below this are rounding: no order to measure


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ["step", "ns_per_simulated_s", "times_real_time", "play_error_median_m",
                    "play_error_p90_m", "play_impact_time_error_s"] + CLOSED_FORMS:
            r[key] = float(r[key]) if r.get(key) not in (None, "") else None
        r["substeps"] = int(r["substeps"])
        r["closed_form_error"] = max(r[k] for k in CLOSED_FORMS if r[k] is not None)
    return rows


def order(rows, model, integrator, key):
    """Slope of log error against log step (one substep), or None where the error is rounding."""
    points = [(math.log(r["step"]), math.log(r[key])) for r in rows
              if r["model"] == model and r["integrator"] == integrator and r["substeps"] == 1
              and r[key] is not None and r[key] > ROUNDING]
    if len(points) < 3:
        return None
    mx = sum(p[0] for p in points) / len(points)
    my = sum(p[1] for p in points) / len(points)
    return (sum((x - mx) * (y - my) for x, y in points) /
            sum((x - mx) ** 2 for x, _ in points))


def pareto(rows, key):
    """The options of the rolling model (the game's physics) that no other beats in both cost
    and error."""
    best, front = math.inf, []
    rolling = [r for r in rows if r["model"] == "rolling" and r[key] > 0]
    for r in sorted(rolling, key=lambda r: (r["ns_per_simulated_s"], r[key])):
        if r[key] < best:
            best = r[key]
            front.append(r)
    return front


def short(value, unit=""):
    if value is None:
        return ""
    if value < ROUNDING and unit == "":
        return "rounding"
    return "%.2g%s" % (value, unit)


def plot(rows, path):
    panels = [("play_error_median_m", "play position error, median (m)",
               "Realistic play: the classic maze, 16 starts x 5 s, against the reference"),
              ("closed_form_error", "worst relative error against closed forms",
               "Closed forms: incline, bounce, slip to roll, resistance, drag, turning board")]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), dpi=100)
    for ax, (key, ylabel, title) in zip(axes, panels):
        for model in MODELS:
            for integrator in INTEGRATORS:
                mine = [r for r in rows if r["model"] == model and r["integrator"] == integrator]
                for n, marker in SUBSTEP_MARKERS.items():
                    # The reference run itself (error 0) is left out.
                    pts = sorted((r["ns_per_simulated_s"] * 1e-3, max(r[key], FLOOR))
                                 for r in mine if r["substeps"] == n and r[key] > 0)
                    if not pts:
                        continue
                    ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker,
                            linestyle=STYLES[model] if n == 1 else "none",
                            color=COLOURS[integrator], markersize=4 if n == 1 else 3,
                            alpha=1.0 if n == 1 else 0.5,
                            label="%s, %s" % (integrator, model) if n == 1 else None)
        front = pareto(rows, key)
        ax.step([r["ns_per_simulated_s"] * 1e-3 for r in front],
                [max(r[key], FLOOR) for r in front], where="post", color="black",
                linewidth=1, alpha=0.6, label="Pareto front (rolling)")
        ax.scatter([r["ns_per_simulated_s"] * 1e-3 for r in front],
                   [max(r[key], FLOOR) for r in front], s=60, facecolors="none",
                   edgecolors="black", linewidths=1)
        for r in rows:
            if r["preset"]:
                ax.annotate(r["preset"], (r["ns_per_simulated_s"] * 1e-3, max(r[key], FLOOR)),
                            textcoords="offset points", xytext=(6, 6), fontsize=9,
                            fontweight="bold")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("cost: CPU µs per simulated second (one core)")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
    axes[0].legend(fontsize=7, loc="lower left")
    fig.text(0.5, 0.005, "lines: one substep, steps 0.1 to 20 ms; ▲ 4 substeps, ■ 16 substeps; "
             "errors at rounding drawn at 1e-16; velocity_verlet and rk4 coincide unless a force "
             "changes over a step (drag)", ha="center", fontsize=8)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(path)


def cpu_name():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def markdown(rows, path):
    out = ["# The speed-accuracy trade", "",
           "Made by `make tradeoff` (bench/tradeoff.cpp, scripts/plot_tradeoff.py) on %s; "
           "do not edit by hand. Cost is the median CPU time per simulated second of the play "
           "scenario on one core; x real time is its inverse. Errors: the play scenario (the "
           "classic maze with its holes filled, the board circling at 0.1 rad from a level "
           "start, played for 5 s from each of 16 phases of the circle) against a reference run "
           "of the same model and phase with rk4 at 1e-4 s x 16 substeps: the marble's distance "
           "from the reference at each whole second, as the median and the 90th percentile over "
           "all 80 (play is chaotic: one instant of one run swings by two orders of magnitude "
           "from phase to phase), and the median over the phases of the largest difference in "
           "the times of the first five impacts; and relative errors against closed forms: a 10 "
           "degree incline from rest (1 s), the first five apexes of a bounce (e = 0.7, from "
           "5 cm), slip to roll (5/7 of 0.7 m/s), rolling resistance (c_rr 0.01, 2 s), air drag "
           "on a level floor (20 m/s, 1 s), a marble carried by a board pitching at a constant "
           "0.5 rad/s (from rest 0.3 m from the pivot, 1 s; the distance it moves along the "
           "board). 'rounding' means below 1e-12." % cpu_name(), "",
           "![error against cost](tradeoff.png)", "",
           "## Presets", "",
           "| preset | model | integrator | step (s) | substeps | µs per simulated s | x real time "
           "| play error, median | play error, 90th percentile | impact time error "
           "| worst closed-form error |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["preset"]:
            out.append("| %s | %s | %s | %g | %d | %.0f | %.0f | %s | %s | %s | %s |" % (
                r["preset"], r["model"], r["integrator"], r["step"], r["substeps"],
                r["ns_per_simulated_s"] * 1e-3, r["times_real_time"],
                short(r["play_error_median_m"], " m"), short(r["play_error_p90_m"], " m"),
                short(r["play_impact_time_error_s"], " s"), short(r["closed_form_error"])))
    out += ["", "## Convergence order", "",
            "The slope of log error against log step (one substep; errors at rounding left out). "
            "'exact' means the error stayed at rounding (below 1e-12) at all but two steps or "
            "fewer. The play scenario is chaotic (a micrometre decides whether a slow impact "
            "bounces), so its error falls with the step only roughly; the closed forms show each "
            "scheme's order.", "",
            "| model | integrator | " + " | ".join(CLOSED_FORMS + ["play, median"]) + " |",
            "|---|---|" + "---|" * (len(CLOSED_FORMS) + 1)]
    for model in MODELS:
        for integrator in INTEGRATORS:
            cells = []
            for key in CLOSED_FORMS + ["play_error_median_m"]:
                values = [r[key] for r in rows if r["model"] == model
                          and r["integrator"] == integrator and r[key] is not None]
                if not values:
                    cells.append("")
                    continue
                k = order(rows, model, integrator, key)
                cells.append("%.1f" % k if k is not None else "exact")
            out.append("| %s | %s | %s |" % (model, integrator, " | ".join(cells)))
    out += ["", "## Every option", "",
            "| model | integrator | step (s) | substeps | µs per simulated s | x real time "
            "| play median (m) | play p90 (m) | impact times (s) | " + " | ".join(CLOSED_FORMS) +
            " |",
            "|---|---|---|---|---|---|---|---|---|" + "---|" * len(CLOSED_FORMS)]
    for r in rows:
        out.append("| %s | %s | %g | %d | %.0f | %.0f | %s | %s | %s | %s |" % (
            r["model"], r["integrator"], r["step"], r["substeps"], r["ns_per_simulated_s"] * 1e-3,
            r["times_real_time"], short(r["play_error_median_m"]), short(r["play_error_p90_m"]),
            short(r["play_impact_time_error_s"]), " | ".join(short(r[k]) for k in CLOSED_FORMS)))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    rows = read(sys.argv[1])
    markdown(rows, sys.argv[2])
    plot(rows, sys.argv[3])
    print("wrote %s and %s from %d options" % (sys.argv[2], sys.argv[3], len(rows)))


if __name__ == "__main__":
    main()
