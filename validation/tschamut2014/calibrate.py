#!/usr/bin/python3
"""Calibration of the Tschamut 2014 case's one free parameter, the meadow's rolling friction.

Usage: calibrate.py [--talus build/talus] [--out /tmp/tschamut-calibration]

Runs the case (calibration_runs.vrt, scenario.toml) in fast and in full mode for each rolling
friction of a grid, with materials.toml's other values, and prints the simulated median runout
of each mode against the observed one (compare.py). It reads no observation but the 18
calibration runs of calibration_runs.csv. The chosen value is the one whose larger error of the
two modes is smallest; docs/validation.md gives the table this script printed.
"""
import argparse
import os
import re
import subprocess
import sys

import compare

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GRID = [0.14, 0.16, 0.18, 0.20, 0.22, 0.24, 0.28, 0.32, 0.40]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--out", default="/tmp/tschamut-calibration")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    observed = compare.observed()["median_m"]
    base = open(os.path.join(HERE, "materials.toml")).read()
    print("rolling_friction  fast median m  full median m  (observed %.1f m)  larger error" % observed)
    best = None
    for value in GRID:
        materials = os.path.join(args.out, "materials-%.2f.toml" % value)
        with open(materials, "w") as f:
            f.write(re.sub(r"^rolling_friction = [0-9.]+", "rolling_friction = %.2f" % value, base, flags=re.M))
        medians = {}
        for mode in ("fast", "full"):
            out = os.path.join(args.out, "%s-%.2f" % (mode, value))
            subprocess.run([args.talus, "rockfall", "--dem", os.path.join(HERE, "terrain.asc"), "--crs", "local",
                            "--release", os.path.join(HERE, "calibration_runs.vrt"), "--materials", materials,
                            "--scenario", os.path.join(HERE, "scenario.toml"), "--mode", mode, "--out", out],
                           check=True, capture_output=True)
            medians[mode] = compare.simulated(out)["median_m"]
        error = max(abs(m / observed - 1.0) for m in medians.values())
        print("%16.2f  %13.1f  %13.1f  %18s  %11.1f%%" % (value, medians["fast"], medians["full"], "", 100 * error))
        if best is None or error < best[1]:
            best = (value, error)
    print("chosen rolling_friction %.2f (larger error %.1f%%)" % (best[0], 100 * best[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
