#!/usr/bin/python3
"""Full-model failure rates before and after the recovery (issue 38, item 7; docs/rockfall-full.md,
section 5, "Recovery"): spheres, ellipsoids and boxes of several sizes on the sample scene (its own
lithology and vegetation maps, 260 sources) and on the Tschamut 2014 terrain (its 18 release
points, without their own blocks, on the case's meadow materials).

Usage: bench/full_model_failure_rates.py [--talus build/talus] [--out /tmp/talus-failures]
           [--sizes 0.1,1,5] [--sample-runs 15] [--tschamut-runs 220] [--csv FILE]

Each case is one `talus rockfall --mode full` with the default recovery. Its run.json gives, under
"recovery", the runs whose first draw met a failed step (`troubled`: the failures without the
recovery, since a first draw computes exactly what it did before the recovery existed), those
drawn again from a fresh stream (`redrawn`) and those that failed on every draw (`failed`). Writes
one CSV row per case and prints a summary; exit code 1 if any case ended with exit code 3.
Ellipsoids have axes D x 0.5 D x 0.25 D and boxes D x 0.65 D x 0.43 D, the proportions of the
issue's failing blocks (2 x 1 x 0.5 m, 0.46 x 0.30 x 0.20 m).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHAPES = ("sphere", "ellipsoid", "box")
PROPORTIONS = {"sphere": None, "ellipsoid": (1.0, 0.5, 0.25), "box": (1.0, 0.65, 0.43)}
SAMPLE = ["--dem", "sample_dem/dem.tif", "--lithology", "sample_dem/lithology.tif", "--vegetation",
          "sample_dem/vegetation.tif", "--release", "sample_dem/rockfall_release.gpkg"]


def tschamut_inputs(folder):
    """The Tschamut release points as a point layer without attributes, so every point releases the
    case's rock (the calibration runs' own blocks would override it)."""
    points = os.path.join(folder, "tschamut_points.csv")
    with open(os.path.join(ROOT, "validation", "tschamut2014", "calibration_runs.csv")) as f, open(points, "w") as out:
        out.write("id,x,y\n")
        for row in csv.DictReader(f):
            out.write("%s,%s,%s\n" % (row["trajectory_id"], row["x"], row["y"]))
    vrt = os.path.join(folder, "tschamut_points.vrt")
    with open(vrt, "w") as f:
        f.write('<OGRVRTDataSource><OGRVRTLayer name="tschamut_points">'
                '<SrcDataSource relativeToVRT="1">tschamut_points.csv</SrcDataSource>'
                '<SrcLayer>tschamut_points</SrcLayer><GeometryType>wkbPoint</GeometryType>'
                '<GeometryField encoding="PointFromColumns" x="x" y="y"/></OGRVRTLayer></OGRVRTDataSource>\n')
    case = os.path.join(ROOT, "validation", "tschamut2014")
    return ["--dem", os.path.join(case, "terrain.asc"), "--crs", "local", "--release", vrt,
            "--materials", os.path.join(case, "materials.toml")]


def size_argument(shape, size):
    if PROPORTIONS[shape] is None:
        return "%g" % size
    return ",".join("%g" % (size * p) for p in PROPORTIONS[shape])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--out", default="/tmp/talus-failures")
    parser.add_argument("--sizes", default="0.1,1,5")
    parser.add_argument("--sample-runs", type=int, default=15)
    parser.add_argument("--tschamut-runs", type=int, default=220)
    parser.add_argument("--csv", default="/tmp/talus-failures.csv")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scenes = [("sample", SAMPLE, args.sample_runs), ("tschamut", tschamut_inputs(args.out), args.tschamut_runs)]
    rows = []
    for scene, inputs, runs in scenes:
        for shape in SHAPES:
            for size in (float(s) for s in args.sizes.split(",")):
                out = os.path.join(args.out, "%s-%s-%g" % (scene, shape, size))
                command = [args.talus, "rockfall", *inputs, "--out", out, "--mode", "full", "--runs", str(runs),
                           "--block-shape", shape, "--block-size", size_argument(shape, size),
                           "--project", "off", "--intensity", "none"]
                start = time.monotonic()
                result = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
                seconds = time.monotonic() - start
                recovery = {"troubled": "", "redrawn": "", "failed": ""}
                simulated = ""
                if result.returncode == 0:
                    with open(os.path.join(out, "run.json")) as f:
                        record = json.load(f)
                    recovery = record["recovery"]
                    simulated = record["counts"]["trajectories"] + recovery["failed"]
                error = result.stderr.strip().splitlines()[-1] if result.returncode != 0 else ""
                rows.append([scene, shape, size, runs, result.returncode, simulated, recovery["troubled"],
                             recovery["redrawn"], recovery["failed"], "%.1f" % seconds, error])
                print("%-8s %-9s %4g m: exit %d, %s trajectories, first draws failed %s, redrawn %s, failed %s, %.0f s %s"
                      % (scene, shape, size, result.returncode, simulated, recovery["troubled"], recovery["redrawn"],
                         recovery["failed"], seconds, error[:160]), flush=True)
    with open(args.csv, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["scene", "shape", "size_m", "runs_per_source", "exit_code", "trajectories",
                         "first_draw_failed", "redrawn", "failed", "seconds", "error"])
        writer.writerows(rows)
    failed = [r for r in rows if r[4] != 0]
    print("%d cases, %d failed cases, %.0f s" % (len(rows), len(failed), sum(float(r[9]) for r in rows)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
