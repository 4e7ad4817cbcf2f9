#!/usr/bin/python3
"""The choice of the default debris-flow material against the empirical laws (README.md beside
this file, "Calibration").

Usage:
  calibration.py [--talus build/talus] [--out out/empirical-laws-calibration] [--docs docs]

Runs empirical_laws.py once per candidate Voellmy rheology (friction mu, turbulence xi, yield
stress tau_y) on every site at 10^2 to 10^5 m3 with particles twice the script's, and tabulates
for each: the runs inside each law's band, the slope of log10(H/L) on log10(V) over the runs the
DEM does not bound (Corominas: -0.105), and the median ratios of L to Rickenmann's and of B to
LAHARZ's. Writes OUT/calibration.csv, and with --docs DIR copies it to
DIR/mudflow-empirical-laws-calibration.csv.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# (mu, xi m/s2, tau_y Pa): the former default (0.2, 200, 0), the former case scenario and the
# rock-avalanche preset (0.1, 500, 0), the yield stresses around the chosen one, and the chosen
# one's neighbours in mu and xi inside the back-analysed ranges (docs/mudflow.md, "Materials").
CANDIDATES = [(0.2, 200, 0), (0.1, 500, 0), (0.1, 500, 300), (0.1, 500, 1000), (0.1, 500, 3000),
              (0.05, 500, 1000), (0.15, 500, 1500), (0.1, 1000, 1000), (0.2, 200, 1000)]
VOLUMES = "100,1000,10000,100000"
COLUMNS = ["mu", "xi_m_s2", "tau_y_pa", "runs", "runs_not_bounded_by_the_dem", "rickenmann_inside",
           "corominas_inside", "laharz_inside", "corominas_slope", "corominas_slope_inside", "median_L_ratio",
           "median_B_ratio"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "empirical-laws-calibration"))
    parser.add_argument("--docs", help="also copy calibration.csv into this folder")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for mu, xi, tau in CANDIDATES:
        name = "mu%g-xi%g-tau%g" % (mu, xi, tau)
        folder = os.path.join(args.out, name)
        command = [sys.executable, os.path.join(HERE, "empirical_laws.py"), "--talus", args.talus, "--out", folder,
                   "--voellmy", "%g,%g,%g" % (mu, xi, tau), "--volumes", VOLUMES, "--coarsen", "2"]
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit("%s failed (exit %d):\n%s" % (" ".join(command), done.returncode, done.stderr[-2000:]))
        with open(os.path.join(folder, "summary.json")) as f:
            summary = json.load(f)
        row = {"mu": mu, "xi_m_s2": xi, "tau_y_pa": tau, "runs": summary["runs"],
               "runs_not_bounded_by_the_dem": summary["runs_not_bounded_by_the_dem"],
               "rickenmann_inside": summary["inside"]["rickenmann"], "corominas_inside": summary["inside"]["corominas"],
               "laharz_inside": summary["inside"]["laharz"], "corominas_slope": "%.3f" % summary["corominas_slope"],
               "corominas_slope_inside": summary["corominas_slope_inside"],
               "median_L_ratio": "%.2f" % summary["median_L_ratio"], "median_B_ratio": "%.2f" % summary["median_B_ratio"]}
        rows.append(row)
        print("mu %-4g xi %-5g tau_y %-5g | inside: Rickenmann %d, Corominas %d, LAHARZ %d of %d | slope %s | "
              "median L/L_R %s, B/B_LZ %s" % (mu, xi, tau, row["rickenmann_inside"], row["corominas_inside"],
                                              row["laharz_inside"], row["runs"], row["corominas_slope"],
                                              row["median_L_ratio"], row["median_B_ratio"]), flush=True)
    path = os.path.join(args.out, "calibration.csv")
    with open(path, "w", newline="") as f:
        out = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        out.writeheader()
        out.writerows(rows)
    if args.docs:
        shutil.copy(path, os.path.join(args.docs, "mudflow-empirical-laws-calibration.csv"))


if __name__ == "__main__":
    main()
