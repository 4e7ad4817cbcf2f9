#!/usr/bin/python3
"""When Talus's mud reaches the side channel of avaAlr (docs/validation.md, point 11).

Usage: side_channel_timing.py TALUS_OUT

TALUS_OUT is the --out folder of the case's command (validation/avaalr_com1dfa/README.md) run
with `--snapshots SECONDS`, so that it holds particles.gpkg. For every snapshot, prints as a
Markdown table the share of the mass in the side channel beyond the low ridge east of the fan
(rows 440-540 of the 5 m grid, east of the line column = 128 + 0.6 (row - 460)), and the mass
passing the knob that parts the flow above it (rows 415-460), with the particles' mean speed and
depth in each. com1DFA keeps only its peak fields, so only Talus's side of this can be shown.
"""
import argparse
import pathlib
import sys

import numpy as np
from osgeo import gdal, ogr

gdal.UseExceptions()
ogr.UseExceptions()


def beyond_the_ridge(row, col):
    """The side channel: east of the low ridge between it and the fan's left bank."""
    return (row > 440) & (row < 540) & (col > 128 + 0.6 * (row - 460))


def at_the_knob(row, col):
    """The rows of the 5 m grid where the knob splits the flow (docs/validation.md, point 8)."""
    return (row >= 415) & (row <= 460)


def read_particles(path, geotransform):
    """Time (s), grid row and column, mass (kg), speed (m/s) and depth (m) of every particle record."""
    dataset = ogr.Open(str(path))
    layer = dataset.GetLayer(0)
    records = []
    for feature in layer:
        point = feature.GetGeometryRef()
        col = (point.GetX() - geotransform[0]) / geotransform[1]
        row = (point.GetY() - geotransform[3]) / geotransform[5]
        records.append((feature["time_s"], row, col, feature["mass_kg"], feature["speed_m_s"], feature["depth_m"]))
    return np.array(records)


def zone_row(records, zone, total):
    """Mass share (%), particle count, mean speed (m/s) and mean depth (m) in a zone."""
    mass = records[zone, 3]
    if mass.size == 0:
        return "0.0% | 0 | - | -"
    return (f"{100.0 * mass.sum() / total:.1f}% | {mass.size} | {records[zone, 4].mean():.1f} | "
            f"{records[zone, 5].mean():.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("talus_out", type=pathlib.Path)
    parser.add_argument("--data", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parents[2] / "data",
                        help="the folder of the real data sets (default: the repository's data/)")
    args = parser.parse_args()
    snapshots = args.talus_out / "particles.gpkg"
    if not snapshots.exists():
        print(f"side_channel_timing.py: {snapshots}: not found; run the case with --snapshots SECONDS", file=sys.stderr)
        sys.exit(2)
    dem = args.data / "tirol_alr" / "avaAlr.tif"
    if not dem.exists():
        print(f"side_channel_timing.py: {dem}: not found; pass the data folder with --data", file=sys.stderr)
        sys.exit(2)
    geotransform = gdal.Open(str(dem)).GetGeoTransform()
    records = read_particles(snapshots, geotransform)
    print("| time (s) | side channel: mass | particles | speed (m/s) | depth (m) "
          "| knob: mass | particles | speed (m/s) | depth (m) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for time in np.unique(records[:, 0]):
        now = records[:, 0] == time
        total = records[now, 3].sum()
        row, col = records[:, 1], records[:, 2]
        side = zone_row(records, now & beyond_the_ridge(row, col), total)
        knob = zone_row(records, now & at_the_knob(row, col), total)
        print(f"| {time:.1f} | {side} | {knob} |")


if __name__ == "__main__":
    main()
