#!/usr/bin/python3
"""Chart of the mud-flow speed-accuracy sweep (bench/mudflow_speed_accuracy.py's CSV).

Three panels share the horizontal axis, the CPU time of a run (s, log scale): the deposit-area
overlap (IoU) with the reference, the root mean square difference of the maximum flow depth,
and the runout difference (m). Circles are uniform runs, triangles adaptive ones; the colour is
the finest particle size. The reference (uniform, finest size) is the black dash-dotted line of
its CPU time. Reruns with another seed give the seed noise of each metric at their particle
size: dashed horizontal lines in the colour of the size. Runs whose status is not "ok" are named on stderr and in the key.

Usage: /usr/bin/python3 bench/plot_mudflow_speed_accuracy.py IN.csv OUT.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.ticker import FuncFormatter  # noqa: E402
from speed_accuracy_csv import read_rows  # noqa: E402

NUMBERS = ("particle_size_m", "cpu_s", "deposit_iou", "flow_depth_rms_m", "runout_error_m")
COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")
# Runout differences of exactly 0 m are drawn at this floor of the log axis (m).
RUNOUT_FLOOR = 1.0
# Log-axis tick labels as plain numbers (50, not 5 x 10^1); minor ticks labelled at 2 and 5 only.
PLAIN_NUMBER = FuncFormatter(lambda value, _: f"{value:g}")
TWO_AND_FIVE = FuncFormatter(lambda value, _: f"{value:g}" if f"{value:.0e}"[0] in "25" else "")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_mudflow_speed_accuracy.py IN.csv OUT.png")
    rows, left_out = read_rows(sys.argv[1], NUMBERS)
    reference = rows[0]
    noise = [row for row in rows if row["seed"] != "1"]
    points = [row for row in rows[1:] if row["seed"] == "1"]
    sizes = sorted({row["particle_size_m"] for row in rows})
    colour = {size: COLOURS[k % len(COLOURS)] for k, size in enumerate(sizes)}

    figure, panels = plt.subplots(1, 3, figsize=(15, 5.4), sharex=True)
    iou_axes, depth_axes, runout_axes = panels
    metrics = ((iou_axes, "deposit_iou", lambda v: v), (depth_axes, "flow_depth_rms_m", lambda v: v),
               (runout_axes, "runout_error_m", lambda v: max(abs(v), RUNOUT_FLOOR)))
    for row in points:
        marker = "^" if row["adaptive"] == "on" else "o"
        for axes, key, shown in metrics:
            axes.plot(row["cpu_s"], shown(row[key]), marker, color=colour[row["particle_size_m"]], markersize=8)
            axes.annotate(f"{row['particle_size_m']:.3g}", (row["cpu_s"], shown(row[key])), textcoords="offset points",
                          xytext=(6, 3), fontsize=7, color=colour[row["particle_size_m"]])
    for row in noise:
        for axes, key, shown in metrics:
            axes.axhline(shown(row[key]), color=colour[row["particle_size_m"]], linestyle="--", linewidth=1,
                         label=f"seed noise at {row['particle_size_m']:.3g} m (uniform, seed 2 against seed 1)")
    for axes in panels:
        axes.axvline(reference["cpu_s"], color="black", linestyle="-.", linewidth=1,
                     label=f"CPU time of the reference, {reference['configuration']}")
        axes.set_xscale("log")
        axes.xaxis.set_major_formatter(PLAIN_NUMBER)
        axes.xaxis.set_minor_formatter(TWO_AND_FIVE)
        axes.set_xlabel("CPU time of the run (s, log scale)")
        axes.grid(True, which="both", alpha=0.3)
    iou_axes.set_ylabel("deposit-area IoU with the reference (-)")
    iou_axes.set_title("Deposit area (depth > 0.05 m)")
    depth_axes.set_ylabel("RMS difference of flow_depth_max (m)")
    depth_axes.set_title("Maximum flow depth")
    runout_axes.set_yscale("log")
    runout_axes.set_ylabel("|runout error| (m, log scale; < 1 m drawn at 1)")
    runout_axes.set_title("Runout from the release centroid")

    handles, labels = iou_axes.get_legend_handles_labels()
    for size in sizes:
        handles.append(plt.Line2D([], [], color=colour[size], marker="s", linestyle=""))
        labels.append(f"finest particles {size:.3g} m")
    handles += [plt.Line2D([], [], color="grey", marker="o", linestyle=""),
                plt.Line2D([], [], color="grey", marker="^", linestyle="")]
    labels += ["uniform particles", "adaptive, the default (fission, fusion and crowded fusion, individual steps)"]
    figure.legend(handles, labels, loc="lower center", ncol=3, fontsize=8, frameon=False)
    title = "Mud flow on the sample scene: speed against accuracy (reference: uniform finest particles)"
    if left_out:
        title += "\nleft out: " + ", ".join(left_out)
    figure.suptitle(title)
    figure.tight_layout(rect=(0, 0.14, 1, 1))
    figure.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
