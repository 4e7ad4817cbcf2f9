#!/usr/bin/python3
"""Full-model robustness sweep (issue 16, Deliver 1): every block shape and size on the sample
scene (its own lithology map, 260 sources) and, for every built-in lithology class, on the
Tschamut 2014 terrain (18 release points); one run per source.

Usage: bench/full_model_sweep.py [--talus build/talus] [--out /tmp/talus-sweep] [--csv FILE]

Each case is one `talus rockfall --mode full` over the whole scene. On Tschamut the materials
table's default lithology is the case's class and there is no lithology raster, so that the
whole slope is that class. A case fails when talus exits with code 3 (a trajectory's numerical failure); its
error line names the source and run and the command that reruns it. Writes one CSV row per case
(scene, shape, size_m, lithology, exit_code, trajectories, seconds, error) and prints a summary.
The figures are in docs/rockfall-full.md, section 5.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHAPES = ("sphere", "ellipsoid", "box")
SIZES = (0.1, 0.2, 0.37, 0.5, 1.0, 2.0, 5.0)
CLASSES = tuple(range(8))
SAMPLE = ["--dem", "sample_dem/dem.tif", "--lithology", "sample_dem/lithology.tif", "--vegetation",
          "sample_dem/vegetation.tif", "--release", "sample_dem/rockfall_release.gpkg"]
TSCHAMUT = ["--dem", "validation/tschamut2014/terrain.asc", "--crs", "local",
            "--release", "validation/tschamut2014/calibration_runs.vrt"]


def materials_with_default(lithology, folder):
    text = open(os.path.join(ROOT, "docs", "materials-default.toml")).read()
    text = re.sub(r"^default_lithology = \d+", "default_lithology = %d" % lithology, text, flags=re.M)
    path = os.path.join(folder, "materials-%d.toml" % lithology)
    with open(path, "w") as f:
        f.write(text)
    return path


def size_argument(shape, size):
    # Ellipsoids and boxes with axes D x 0.8 D x 0.6 D, spheres of diameter D.
    return "%g" % size if shape == "sphere" else "%g,%g,%g" % (size, 0.8 * size, 0.6 * size)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--out", default="/tmp/talus-sweep")
    parser.add_argument("--csv", default="/tmp/talus-sweep.csv")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    cases = [("sample", "map", SAMPLE)]
    cases += [("tschamut", str(c), TSCHAMUT + ["--materials", materials_with_default(c, args.out)]) for c in CLASSES]
    rows = []
    for scene, lithology, inputs in cases:
        for shape in SHAPES:
            for size in SIZES:
                out = os.path.join(args.out, "%s-%s-%s-%g" % (scene, lithology, shape, size))
                command = [args.talus, "rockfall", *inputs, "--out", out,
                           "--mode", "full", "--runs", "1", "--block-shape", shape,
                           "--block-size", size_argument(shape, size)]
                start = time.monotonic()
                result = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
                seconds = time.monotonic() - start
                trajectories = 0
                if result.returncode == 0:
                    with open(os.path.join(out, "run.json")) as f:
                        trajectories = json.load(f)["counts"]["trajectories"]
                error = result.stderr.strip().splitlines()[-1] if result.returncode != 0 else ""
                rows.append([scene, shape, size, lithology, result.returncode, trajectories, "%.2f" % seconds, error])
                print("%-8s class %-3s %-9s %5g m: exit %d, %4d trajectories, %6.2f s %s" %
                      (scene, lithology, shape, size, result.returncode, trajectories, seconds, error[:120]),
                      flush=True)
    with open(args.csv, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["scene", "shape", "size_m", "lithology", "exit_code", "trajectories", "seconds", "error"])
        writer.writerows(rows)
    failed = [r for r in rows if r[4] != 0]
    print("%d cases, %d trajectories, %d failed cases, %.0f s" %
          (len(rows), sum(r[5] for r in rows), len(failed), sum(float(r[6]) for r in rows)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
