#!/usr/bin/python3
"""Convergence of the rock-fall maps against the number of runs on the sample scene (issue 17, item 2).

Runs the README's `talus rockfall` command (sample_dem/: 260 release points, fast mode, seed 1)
with `--runs N` for each N of --runs and with `--runs auto`, and writes one CSV row per run:
  runs                 --runs as given
  trajectories         trajectories simulated (run.json counts)
  runs_median, runs_max  runs per source: median and largest (run.json runs)
  simulate_s           the run's simulation time (run.json timings_s; reading and writing excluded)
  reach_change, energy_change  the convergence measure of run.json (-; docs/hazard-statistics.md,
                       "Convergence"), converged and runs_suggested with it
  reached_cells        cells with passages > 0
  cells_above_1000kJ   cells with energy_max > 1000 kJ; p95_cells_above_1000kJ with energy_p95
  reach_l1_to_reference  sum |reach probability per released block - the reference's| / sum of the
                       reference's (-), the reference being the largest fixed --runs
and draws the changes against the runs (log-log, with a 1 / sqrt(runs) line) into a PNG.

Usage (from the repository root):
  /usr/bin/python3 bench/rockfall_convergence_sweep.py docs/rockfall-convergence.csv docs/rockfall-convergence.png
      [--talus build/talus] [--runs 10,20,40,80,100,160,320,640,1000,1280] [--threads 2] [--work DIR] [--reuse]
--work keeps each run's layers (default: build/rockfall-convergence-runs, ignored by git); with
--reuse, a run whose folder already holds its run.json is read again instead of run.
"""
import argparse
import csv
import json
import subprocess
from pathlib import Path

import numpy as np
from osgeo import gdal

gdal.UseExceptions()

ROOT = Path(__file__).resolve().parent.parent
SAMPLE = ROOT / "sample_dem"
FIELDS = ("runs", "trajectories", "runs_median", "runs_max", "simulate_s", "reach_change", "energy_change", "converged",
          "runs_suggested", "reached_cells", "cells_above_1000kJ", "p95_cells_above_1000kJ", "reach_l1_to_reference")


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", type=Path)
    parser.add_argument("png", type=Path)
    parser.add_argument("--talus", type=Path, default=ROOT / "build" / "talus")
    parser.add_argument("--runs", default="10,20,40,80,100,160,320,640,1000,1280")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--work", type=Path, default=ROOT / "build" / "rockfall-convergence-runs")
    parser.add_argument("--reuse", action="store_true", help="read the runs already in --work instead of running them")
    return parser.parse_args()


def band(folder, layer):
    dataset = gdal.Open(str(folder / f"{layer}.tif"))  # held while its band is read
    return dataset.GetRasterBand(1).ReadAsArray().astype(np.float64)


def run(arguments, runs):
    """One talus rockfall run; its folder."""
    out = arguments.work / f"runs_{runs}"
    if arguments.reuse and (out / "run.json").exists():
        return out
    subprocess.run([str(arguments.talus), "rockfall", "--dem", str(SAMPLE / "dem.tif"), "--lithology",
                    str(SAMPLE / "lithology.tif"), "--vegetation", str(SAMPLE / "vegetation.tif"), "--release",
                    str(SAMPLE / "rockfall_release.gpkg"), "--out", str(out), "--runs", runs, "--threads",
                    str(arguments.threads)], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out


def row(out, runs, reference_reach):
    record = json.loads((out / "run.json").read_text())
    passages, energy_max, energy_p95 = band(out, "passages"), band(out, "energy_max"), band(out, "energy_p95")
    convergence = record["convergence"]
    per_block = np.where(passages > 0, passages, 0) / record["counts"]["trajectories"]
    return {"runs": runs, "trajectories": record["counts"]["trajectories"],
            "runs_median": record["runs"]["per_source_median"], "runs_max": record["runs"]["per_source_max"],
            "simulate_s": round(record["timings_s"]["simulate"], 2),
            "reach_change": round(convergence["reach_change"], 5), "energy_change": round(convergence["energy_change"], 5),
            "converged": convergence["converged"], "runs_suggested": convergence["runs_suggested"],
            "reached_cells": int((passages > 0).sum()), "cells_above_1000kJ": int((energy_max > 1000).sum()),
            "p95_cells_above_1000kJ": int((energy_p95 > 1000).sum()),
            "reach_l1_to_reference": "" if runs == "auto" else
            round(float(np.abs(per_block - reference_reach).sum() / reference_reach.sum()), 5)}


def plot(rows, png):
    """Left: the convergence measure against the runs; right: the extremes, which keep growing."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fixed = [r for r in rows if r["runs"] != "auto"]
    auto = [r for r in rows if r["runs"] == "auto"]
    n = np.array([int(r["runs"]) for r in fixed], dtype=float)
    mean_auto = auto[0]["trajectories"] / 260.0 if auto else None
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    left.loglog(n, [r["reach_change"] for r in fixed], "o-", label="reach change (fixed --runs)")
    left.loglog(n, [r["energy_change"] for r in fixed], "s-", label="energy change (fixed --runs)")
    left.loglog(n, fixed[0]["energy_change"] * np.sqrt(n[0] / n), ":", color="grey", label="1 / sqrt(runs)")
    if auto:
        left.loglog([mean_auto], [auto[0]["reach_change"]], "o", color="C0", mfc="none", ms=10,
                    label="--runs auto (at its mean runs per source)")
        left.loglog([mean_auto], [auto[0]["energy_change"]], "s", color="C1", mfc="none", ms=10)
    left.axhline(0.05, color="k", lw=0.8, ls="--", label="default tolerance 0.05")
    left.set_xlabel("runs per source")
    left.set_ylabel("change over the last doubling (-)")
    left.set_title("Convergence measure (run.json)")
    left.legend(fontsize=8)
    left.grid(True, which="both", lw=0.3)
    for key, style, label in (("reached_cells", "o-", "cells reached (passages > 0)"),
                              ("cells_above_1000kJ", "s-", "cells with energy_max > 1000 kJ"),
                              ("p95_cells_above_1000kJ", "^-", "cells with energy_p95 > 1000 kJ")):
        line, = right.semilogx(n, [r[key] for r in fixed], style, label=label)
        if auto:
            right.semilogx([mean_auto], [auto[0][key]], style[0], color=line.get_color(), mfc="none", ms=10)
    right.set_xlabel("runs per source (open symbols: --runs auto)")
    right.set_ylabel("cells (5 m)")
    right.set_title("Extremes of the sample: they keep growing")
    right.legend(fontsize=8)
    right.grid(True, which="both", lw=0.3)
    figure.suptitle("Sample scene, 260 sources, fast mode, seed 1")
    figure.tight_layout()
    figure.savefig(png, dpi=100)


def main():
    arguments = parse_arguments()
    arguments.work.mkdir(parents=True, exist_ok=True)
    runs = arguments.runs.split(",") + ["auto"]
    folders = {r: run(arguments, r) for r in runs}
    largest = max(runs[:-1], key=int)
    reference = folders[largest]
    reference_record = json.loads((reference / "run.json").read_text())
    reference_passages = band(reference, "passages")
    reference_reach = np.where(reference_passages > 0, reference_passages, 0) / reference_record["counts"]["trajectories"]
    rows = [row(folders[r], r, reference_reach) for r in runs]
    with open(arguments.csv, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, arguments.png)
    for r in rows:
        print(r)


if __name__ == "__main__":
    main()
