#!/usr/bin/python3
"""Speed against accuracy of the mud flow on the sample scene (issue 5, "Benchmarks and chart").

Runs `talus mudflow` on the sample scene (sample_dem/: DEM, lithology, vegetation and the gully
release of mudflow_release.gpkg, 14,445 m3) for every particle size x adaptivity (on / off),
every other parameter at its default (Voellmy rheology), and compares each run's layers with
those of the reference: uniform particles of the finest size. Each run goes on until the flow
stops (kinetic energy below 1% of its peak) or --duration. The uniform run of every size is run
again with the next seed (the release jitter): the noise floor of each metric at that size
(those rows compare the rerun with the first run of its size, column compared_with; every other
row compares with the reference). Writes one CSV row per run (columns and units:
docs/mudflow-speed-accuracy.md); bench/plot_mudflow_speed_accuracy.py draws the chart.

Metrics against the reference, on the DEM's 5 m cells:
  deposit_iou        cells with deposit_depth > DEPOSIT_THRESHOLD in both runs / in either (-)
  flow_depth_rms_m   root mean square of the flow_depth_max difference over the cells where
                     either run's flow_depth_max exceeds DEPOSIT_THRESHOLD (m)
  runout_m           horizontal distance from the release polygon's centroid to the farthest
                     cell centre with deposit_depth > DEPOSIT_THRESHOLD (m); runout_error_m is
                     this minus the reference's
Times: wall_s is the run's simulation time from its run.json (reading and writing the files
excluded); cpu_s the CPU time of the whole `talus mudflow` process, all threads (user + system,
reading and writing included: under 1 s).

Usage (from the repository root; the machine's cores are shared, so runs default to one thread
each, two runs at a time):
  /usr/bin/python3 bench/mudflow_speed_accuracy.py OUT.csv [--talus build/talus] [--sizes 1.25,1.6667,2.5,5]
      [--threads 1] [--jobs 2] [--duration 300] [--time-limit 1200] [--work DIR] [--reuse]
--work keeps each run's layers (default: build/mudflow-speed-accuracy-runs, ignored by git); with
--reuse, a run whose folder already holds the layers, run.json and measure.json of the same
command is read again instead of run.
"""
import argparse
import csv
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from osgeo import gdal, ogr

gdal.UseExceptions()

ROOT = Path(__file__).resolve().parent.parent
SAMPLE = ROOT / "sample_dem"
DEPOSIT_THRESHOLD = 0.05  # m: a cell holds deposit (or was reached) above this depth
FIELDS = ("configuration", "compared_with", "particle_size_m", "adaptive", "seed", "status", "threads", "wall_s", "cpu_s",
          "particle_steps", "particle_steps_per_cpu_s", "initial_particles", "peak_particles", "final_particles",
          "splits", "merges", "simulated_s", "end", "deposit_cells", "deposit_iou", "flow_depth_rms_m",
          "runout_m", "runout_error_m", "cpu_speedup_over_reference")


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", type=Path)
    parser.add_argument("--talus", type=Path, default=ROOT / "build" / "talus")
    parser.add_argument("--sizes", default="1.25,1.6667,2.5,5", help="particle sizes (m); the finest is the reference")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=2, help="runs at a time")
    parser.add_argument("--duration", type=float, default=300.0, help="longest simulated time (s)")
    parser.add_argument("--time-limit", type=float, default=1200.0, help="wall time per run (s)")
    parser.add_argument("--work", type=Path)
    parser.add_argument("--reuse", action="store_true")
    arguments = parser.parse_args()
    arguments.sizes = sorted(float(text) for text in arguments.sizes.split(","))
    if arguments.work is None:
        arguments.work = ROOT / "build" / "mudflow-speed-accuracy-runs"
    return arguments


def size_text(size):
    return f"{size:g}"


class Run:
    """One `talus mudflow` run: its configuration, command, and (once finished) outcome."""

    def __init__(self, size, adaptive, seed, arguments):
        self.size, self.adaptive, self.seed = size, adaptive, seed
        self.label = f"{'adaptive' if adaptive else 'uniform'} {size_text(size)} m" + (
            f" seed {seed}" if seed != 1 else "")
        self.folder = arguments.work / self.label.replace(" ", "_").replace(",", "")
        self.command = [str(arguments.talus), "mudflow", "--dem", str(SAMPLE / "dem.tif"),
                        "--lithology", str(SAMPLE / "lithology.tif"), "--vegetation", str(SAMPLE / "vegetation.tif"),
                        "--release", str(SAMPLE / "mudflow_release.gpkg"), "--out", str(self.folder),
                        "--particle-size", size_text(size), "--adaptive", "on" if adaptive else "off",
                        "--seed", str(seed), "--threads", str(arguments.threads),
                        "--duration", f"{arguments.duration:g}"]
        self.status = "not run"
        self.cpu_seconds = math.nan
        self.record = None

    def measure_path(self):
        return self.folder / "measure.json"

    def reusable(self):
        if not self.measure_path().exists() or not (self.folder / "run.json").exists():
            return False
        return json.loads(self.measure_path().read_text())["command"] == self.command

    def read_back(self):
        measure = json.loads(self.measure_path().read_text())
        self.status, self.cpu_seconds = measure["status"], measure["cpu_s"]
        if self.status == "ok":
            self.record = json.loads((self.folder / "run.json").read_text())

    def finish(self, status, cpu_seconds):
        self.status, self.cpu_seconds = status, cpu_seconds
        self.folder.mkdir(parents=True, exist_ok=True)
        self.measure_path().write_text(json.dumps({"command": self.command, "status": status, "cpu_s": cpu_seconds}))
        if status == "ok":
            self.record = json.loads((self.folder / "run.json").read_text())


def run_all(runs, arguments):
    """Runs at most --jobs at a time, each killed after --time-limit; CPU time from wait4."""
    pending = [run for run in runs if not (arguments.reuse and run.reusable())]
    for run in runs:
        if run not in pending:
            run.read_back()
            print(f"reused: {run.label} ({run.status})", file=sys.stderr)
    started = {}
    while pending or started:
        while pending and len(started) < arguments.jobs:
            run = pending.pop(0)
            run.folder.parent.mkdir(parents=True, exist_ok=True)
            log = open(run.folder.parent / (run.folder.name + ".log"), "w")
            process = subprocess.Popen(run.command, stdout=log, stderr=subprocess.STDOUT)
            started[process.pid] = (run, process, time.monotonic(), log)
            print(f"started: {run.label}", file=sys.stderr)
        time.sleep(0.5)
        for pid in list(started):
            run, process, start, log = started[pid]
            if time.monotonic() - start > arguments.time_limit:
                os.kill(pid, signal.SIGKILL)
                _, code, usage = os.wait4(pid, 0)
                status = "timed_out"
            else:
                finished, code, usage = os.wait4(pid, os.WNOHANG)
                if finished == 0:
                    continue
                if os.WIFEXITED(code):
                    status = "ok" if os.WEXITSTATUS(code) == 0 else f"exit_code_{os.WEXITSTATUS(code)}"
                else:
                    status = "crashed"
            process.returncode = code  # reaped by wait4: Popen must not wait for it again
            log.close()
            run.finish(status, usage.ru_utime + usage.ru_stime)
            print(f"{status}: {run.label} ({time.monotonic() - start:.0f} s)", file=sys.stderr)
            del started[pid]


def read_layer(run, name):
    """A layer as float64 with NaN at nodata."""
    dataset = gdal.Open(str(run.folder / f"{name}.tif"))
    band = dataset.GetRasterBand(1)
    values = band.ReadAsArray().astype(np.float64)
    nodata = band.GetNoDataValue()
    if nodata is not None:
        values[values == nodata] = np.nan
    return values, dataset.GetGeoTransform()


def release_centroid():
    """(x, y) of the centroid of the release polygons (m, the DEM's CRS)."""
    source = ogr.Open(str(SAMPLE / "mudflow_release.gpkg"))
    union = None
    for feature in source.GetLayer(0):
        geometry = feature.GetGeometryRef().Clone()
        union = geometry if union is None else union.Union(geometry)
    centroid = union.Centroid()
    return centroid.GetX(), centroid.GetY()


def runout(deposit, transform, centre):
    """Largest horizontal distance (m) from `centre` to a cell centre holding deposit."""
    rows, cols = np.nonzero(np.nan_to_num(deposit) > DEPOSIT_THRESHOLD)
    if rows.size == 0:
        return math.nan
    x = transform[0] + (cols + 0.5) * transform[1] + (rows + 0.5) * transform[2]
    y = transform[3] + (cols + 0.5) * transform[4] + (rows + 0.5) * transform[5]
    return float(np.max(np.hypot(x - centre[0], y - centre[1])))


def compare(run, reference, finest_cpu_seconds, centre):
    """The CSV row of one run against `reference` (a run of the same command but the seed, or
    the finest uniform run); the CPU speed-up is always over the finest uniform run."""
    row = {"configuration": run.label, "compared_with": reference.label, "particle_size_m": run.size, "adaptive": "on" if run.adaptive else "off",
           "seed": run.seed, "status": run.status, "cpu_s": round(run.cpu_seconds, 2)}
    if run.status != "ok":
        return row
    record = run.record
    counts = record["counts"]
    row.update({"threads": record["threads"], "wall_s": round(record["timings_s"]["simulate"], 2),
                "particle_steps": counts["particle_steps"],
                "particle_steps_per_cpu_s": round(counts["particle_steps"] / run.cpu_seconds),
                "initial_particles": counts["particles"]["initial"], "peak_particles": counts["particles"]["peak"],
                "final_particles": counts["particles"]["final"], "splits": counts["splits"],
                "merges": counts["merges"], "simulated_s": record["end"]["simulated_time_s"],
                "end": record["end"]["reason"]})
    deposit, transform = read_layer(run, "deposit_depth")
    flow, _ = read_layer(run, "flow_depth_max")
    reference_deposit, _ = read_layer(reference, "deposit_depth")
    reference_flow, _ = read_layer(reference, "flow_depth_max")
    here, there = np.nan_to_num(deposit) > DEPOSIT_THRESHOLD, np.nan_to_num(reference_deposit) > DEPOSIT_THRESHOLD
    reached = (np.nan_to_num(flow) > DEPOSIT_THRESHOLD) | (np.nan_to_num(reference_flow) > DEPOSIT_THRESHOLD)
    difference = np.nan_to_num(flow)[reached] - np.nan_to_num(reference_flow)[reached]
    distance, reference_distance = runout(deposit, transform, centre), runout(reference_deposit, transform, centre)
    row.update({"deposit_cells": int(here.sum()),
                "deposit_iou": round(float((here & there).sum() / max((here | there).sum(), 1)), 4),
                "flow_depth_rms_m": round(float(np.sqrt(np.mean(difference ** 2))), 4),
                "runout_m": round(distance, 1), "runout_error_m": round(distance - reference_distance, 1),
                "cpu_speedup_over_reference": round(finest_cpu_seconds / run.cpu_seconds, 2)})
    return row


def main():
    arguments = parse_arguments()
    if not arguments.talus.exists():
        sys.exit(f"mudflow_speed_accuracy: error: {arguments.talus} not found (build the talus target, or --talus)")
    finest = arguments.sizes[0]
    runs = [Run(finest, False, 1, arguments)]
    runs += [Run(size, True, 1, arguments) for size in arguments.sizes]
    runs += [Run(size, False, 1, arguments) for size in arguments.sizes[1:]]
    runs += [Run(size, False, 2, arguments) for size in arguments.sizes]
    start = time.monotonic()
    run_all(sorted(runs, key=lambda run: (run.size, run.adaptive, run.seed)), arguments)  # the longest first
    print(f"sweep: {time.monotonic() - start:.0f} s of wall time", file=sys.stderr)
    reference = runs[0]
    if reference.status != "ok":
        sys.exit(f"mudflow_speed_accuracy: error: the reference ({reference.label}) {reference.status}")
    centre = release_centroid()
    with open(arguments.csv, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=FIELDS)
        writer.writeheader()
        for run in runs:
            partner = reference
            if run.seed != 1:
                partner = next(other for other in runs if other.seed == 1 and not other.adaptive and other.size == run.size)
            row = compare(run, partner, reference.cpu_seconds, centre) if partner.status == "ok" else {
                "configuration": run.label, "compared_with": partner.label, "status": f"{partner.label} {partner.status}"}
            writer.writerow(row)


if __name__ == "__main__":
    main()
