#!/usr/bin/python3
"""Chart of the rock-fall speed-against-accuracy sweep (issue 4; docs/architecture.md section 4).

Reads the CSV that build/bench/rockfall_speed_accuracy writes and draws two panels against
the CPU time per trajectory (log scale), each against the finest full model: the runout error
(|relative error of the median| and the Kolmogorov-Smirnov distance of the runout
distributions) and the reach-probability difference (mean absolute difference over the cells
either run reaches, and the share of those cells that only one of the two reaches). Every
marker carries its configuration's number, named in the key under the panels. The reference's
rerun with another seed is drawn as grey lines: the Monte Carlo noise floor. Configurations
whose status is not "ok" (runs that failed numerically, a time-out, a crash) are left out and
named on stderr and in the key.

Usage: /usr/bin/python3 bench/plot_speed_accuracy.py IN.csv OUT.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from speed_accuracy_csv import read_rows  # noqa: E402

# Values that are exactly 0 are drawn at this floor of the log axes (-).
LOG_FLOOR = 1e-4
NUMBERS = ("cpu_ms_per_trajectory", "median_runout_rel_error", "ks_runout", "reach_mean_abs_diff",
           "reach_status_differs_share")
COLOURS = {"full": "tab:blue", "fast": "tab:red"}
# Label offsets (points), cycled so that neighbouring markers' numbers do not sit on each other.
OFFSETS = ((5, 3), (5, -9), (-11, 3), (-11, -9))


def floor(value):
    return max(abs(value), LOG_FLOOR)


def draw_pair(axes, row, number, circle_key, cross_key):
    """One configuration's two metrics on one panel: a circle and a cross, both numbered."""
    colour = COLOURS[row["mode"]]
    x = row["cpu_ms_per_trajectory"]
    offset = OFFSETS[number % len(OFFSETS)]
    for key, marker in ((circle_key, "o"), (cross_key, "x")):
        y = floor(row[key])
        axes.plot(x, y, marker, color=colour, markersize=7)
        axes.annotate(str(number), (x, y), textcoords="offset points", xytext=offset, fontsize=7, color=colour)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_speed_accuracy.py IN.csv OUT.png")
    rows, left_out = read_rows(sys.argv[1], NUMBERS)
    reference = rows[0]
    noise = [r for r in rows[1:] if r["configuration"].endswith("other seed")]
    points = [r for r in rows[1:] if not r["configuration"].endswith("other seed")]

    figure, (runout_axes, reach_axes) = plt.subplots(1, 2, figsize=(12, 6.4), sharex=True)
    for number, row in enumerate(points, start=1):
        draw_pair(runout_axes, row, number, "median_runout_rel_error", "ks_runout")
        draw_pair(reach_axes, row, number, "reach_mean_abs_diff", "reach_status_differs_share")
    for row in noise:
        runout_axes.axhline(floor(row["median_runout_rel_error"]), color="grey", linestyle="--", linewidth=1,
                            label="noise floor of the circles (the reference with another seed)")
        runout_axes.axhline(floor(row["ks_runout"]), color="grey", linestyle=":", linewidth=1,
                            label="noise floor of the crosses")
        reach_axes.axhline(floor(row["reach_mean_abs_diff"]), color="grey", linestyle="--", linewidth=1)
        reach_axes.axhline(floor(row["reach_status_differs_share"]), color="grey", linestyle=":", linewidth=1)
    for axes in (runout_axes, reach_axes):
        axes.axvline(reference["cpu_ms_per_trajectory"], color="black", linestyle="-.", linewidth=1,
                     label=f"time of the reference, {reference['configuration']}" if axes is runout_axes else None)
        axes.set_xscale("log")
        axes.set_yscale("log")
        axes.set_xlabel("CPU time per trajectory (ms, log scale)")
        axes.grid(True, which="both", alpha=0.3)
    runout_axes.plot([], [], "o", color="grey", label="left: |relative error of the median runout|")
    runout_axes.plot([], [], "x", color="grey", label="left: Kolmogorov-Smirnov distance of the runouts")
    runout_axes.plot([], [], "o", color="white", markeredgecolor="grey",
                     label="right: mean |reach-probability difference| over cells either reaches")
    runout_axes.plot([], [], "x", color="grey", label="right: share of those cells reached by only one")
    runout_axes.set_ylabel("runout error against the reference (-)")
    runout_axes.set_title("Runout distribution")
    reach_axes.set_ylabel("reach-probability difference against the reference (-)")
    reach_axes.set_title("Reach-probability map")

    handles, labels = runout_axes.get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.01, 0.0), ncol=2, fontsize=8, frameon=False)
    key = "   ".join(f"{number} {row['configuration']}" for number, row in enumerate(points, start=1))
    if left_out:
        key += "\nleft out: " + ", ".join(left_out)
    figure.text(0.5, 0.135, "blue: full model, red: fast mode.   " + key, ha="center", fontsize=8, wrap=True)
    figure.suptitle("Rock fall on the sample scene: speed against accuracy (reference: the finest full model)")
    figure.tight_layout(rect=(0, 0.17, 1, 1))
    figure.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
