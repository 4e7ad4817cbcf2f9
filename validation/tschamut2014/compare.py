#!/usr/bin/python3
"""Simulated against observed runouts of the Tschamut 2014 calibration runs.

Usage: compare.py OUT_FOLDER [OUT_FOLDER ...]   (folders of `talus rockfall` runs on this case)

Reads calibration_runs.csv (observed release and deposit points) and each folder's
trajectories.gpkg (every run's 3D line: its first vertex is the release, its last the stop) and
prints, for observed and simulated (a rock that never left its release counts as 0 m): the median, 5th and 95th percentile of the horizontal runout
(straight distance from release to stop, m, as observed_runout_m) and the median travel azimuth
(degrees clockwise from north); for each simulated folder also the median and 95th percentile of
the runs' largest kinetic energy (kJ, translation and rotation, the lines' max_energy_kj) and,
over the cells the rocks reached, of jump_height_p95 (m) and velocity_max (m/s).
"""
import csv
import math
import os
import sys

import numpy as np
from osgeo import gdal, ogr

HERE = os.path.dirname(os.path.abspath(__file__))


def summary(runouts, azimuths):
    r = np.asarray(runouts)
    return {"n": len(r), "median_m": float(np.median(r)), "p05_m": float(np.percentile(r, 5)),
            "p95_m": float(np.percentile(r, 95)), "azimuth_deg": float(np.median(azimuths))}


def azimuth(dx, dy):
    return math.degrees(math.atan2(dx, dy)) % 360.0


def observed():
    runouts, azimuths = [], []
    with open(os.path.join(HERE, "calibration_runs.csv")) as f:
        for row in csv.DictReader(f):
            dx = float(row["observed_x"]) - float(row["x"])
            dy = float(row["observed_y"]) - float(row["y"])
            runouts.append(math.hypot(dx, dy))
            azimuths.append(azimuth(dx, dy))
    return summary(runouts, azimuths)


def simulated(folder):
    runouts, azimuths = [], []
    data = ogr.Open(os.path.join(folder, "trajectories.gpkg"))
    for feature in data.GetLayerByName("trajectories"):
        line = feature.GetGeometryRef()
        if line is None:  # a rock that never moved leaves a line of one point, which has no geometry
            runouts.append(0.0)
            continue
        x0, y0 = line.GetX(0), line.GetY(0)
        x1, y1 = line.GetX(line.GetPointCount() - 1), line.GetY(line.GetPointCount() - 1)
        runouts.append(math.hypot(x1 - x0, y1 - y0))
        azimuths.append(azimuth(x1 - x0, y1 - y0))
    return summary(runouts, azimuths)


def energies_and_heights(folder):
    data = ogr.Open(os.path.join(folder, "trajectories.gpkg"))
    energies = [feature.GetField("max_energy_kj") for feature in data.GetLayerByName("trajectories")]
    passages = gdal.Open(os.path.join(folder, "passages.tif")).ReadAsArray() > 0
    jump = gdal.Open(os.path.join(folder, "jump_height_p95.tif")).ReadAsArray()[passages]
    speed = gdal.Open(os.path.join(folder, "velocity_max.tif")).ReadAsArray()[passages]
    quantiles = lambda values: (float(np.median(values)), float(np.percentile(values, 95)))
    return quantiles(energies), quantiles(jump), quantiles(speed)


def main():
    rows = [("observed", observed())] + [(folder, simulated(folder)) for folder in sys.argv[1:]]
    print("%-40s %4s %9s %7s %7s %8s" % ("", "n", "median m", "p05 m", "p95 m", "azimuth"))
    for name, s in rows:
        print("%-40s %4d %9.1f %7.1f %7.1f %8.1f" % (name[-40:], s["n"], s["median_m"], s["p05_m"], s["p95_m"],
                                                     s["azimuth_deg"]))
    print("\n%-40s %19s %21s %21s" % ("", "max energy kJ", "jump_height_p95 m", "velocity_max m/s"))
    for folder in sys.argv[1:]:
        e, j, v = energies_and_heights(folder)
        print("%-40s median %4.1f p95 %4.1f  median %4.2f p95 %4.2f  median %4.1f p95 %4.1f" %
              (folder[-40:], e[0], e[1], j[0], j[1], v[0], v[1]))


if __name__ == "__main__":
    main()
