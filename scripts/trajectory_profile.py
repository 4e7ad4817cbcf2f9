#!/usr/bin/python3
"""Profile plot of one rock-fall trajectory of a `talus rockfall` output folder (issue 17, item 6).

Reads the layer `trajectory_vertices` of OUT/trajectories.gpkg and draws, against the horizontal
distance along the path: the elevation of the rock's centre and, with --dem, of the ground under
it (bilinear between the DEM's cell centres); its kinetic energy (kJ) and speed (m/s); its jump height (m). Writes a PNG.

usage: /usr/bin/python3 scripts/trajectory_profile.py OUT --source N --run K --png PROFILE.png [--dem DEM]

N and K are the source_id and run_id of the line (0-based, as `--only-source` and `--only-run`);
`ogrinfo -al -q OUT/trajectories.gpkg trajectories` lists the saved ones. Runs on Debian's
/usr/bin/python3 (python3-gdal, python3-matplotlib).
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from osgeo import gdal, ogr  # noqa: E402

gdal.UseExceptions()


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", help="output folder of talus rockfall")
    parser.add_argument("--source", type=int, required=True, help="source_id of the trajectory")
    parser.add_argument("--run", type=int, required=True, help="run_id of the trajectory")
    parser.add_argument("--png", required=True, help="the PNG to write")
    parser.add_argument("--dem", help="the run's DEM, to draw the ground under the path")
    return parser.parse_args()


def vertices(out, source, run):
    """The line's vertices in order: (distance_m, z, time_s, speed_m_s, energy_kj, jump_height_m, x, y)."""
    data = ogr.Open(f"{out}/trajectories.gpkg")
    if data is None:
        sys.exit(f"trajectory_profile: {out}/trajectories.gpkg cannot be read")
    layer = data.GetLayerByName("trajectory_vertices")
    if layer is None:
        sys.exit(f"trajectory_profile: {out}/trajectories.gpkg has no trajectory_vertices layer (written before issue 17)")
    layer.SetAttributeFilter(f"source_id = {source} AND run_id = {run}")
    rows = []
    for feature in layer:
        point = feature.GetGeometryRef()
        rows.append((feature.GetField("vertex"), feature.GetField("distance_m"), point.GetZ(), feature.GetField("time_s"),
                     feature.GetField("speed_m_s"), feature.GetField("energy_kj"), feature.GetField("jump_height_m"),
                     point.GetX(), point.GetY()))
    if not rows:
        sys.exit(f"trajectory_profile: no saved trajectory of source {source}, run {run} in {out}/trajectories.gpkg")
    rows.sort()
    return [row[1:] for row in rows]


def ground_under(dem_path, points):
    """The DEM's elevation (m) at each (x, y), bilinear between cell centres; None off the DEM or on nodata."""
    dem = gdal.Open(dem_path)  # kept open while its band is read
    band = dem.GetRasterBand(1)
    values = band.ReadAsArray().astype(float)
    nodata = band.GetNoDataValue()
    x0, dx, _, y0, _, dy = dem.GetGeoTransform()
    heights = []
    for x, y in points:
        col, row = (x - x0) / dx - 0.5, (y - y0) / dy - 0.5
        c, r = int(col // 1), int(row // 1)
        if not (0 <= r < values.shape[0] - 1 and 0 <= c < values.shape[1] - 1):
            heights.append(None)
            continue
        corners = values[r:r + 2, c:c + 2]
        if nodata is not None and (corners == nodata).any():
            heights.append(None)
            continue
        fc, fr = col - c, row - r
        top = corners[0, 0] * (1 - fc) + corners[0, 1] * fc
        bottom = corners[1, 0] * (1 - fc) + corners[1, 1] * fc
        heights.append(float(top * (1 - fr) + bottom * fr))
    return heights


def main():
    args = parse_arguments()
    rows = vertices(args.out, args.source, args.run)
    distance = [r[0] for r in rows]
    figure, (path_axes, energy_axes, jump_axes) = plt.subplots(3, 1, figsize=(9, 8), sharex=True,
                                                                gridspec_kw={"height_ratios": [2, 1, 1]})
    path_axes.plot(distance, [r[1] for r in rows], color="tab:red", label="centre of the rock")
    if args.dem:
        ground = ground_under(args.dem, [(r[6], r[7]) for r in rows])
        path_axes.plot(distance, [g if g is not None else float("nan") for g in ground], color="0.3", label="ground (DEM)")
    path_axes.set_ylabel("elevation (m)")
    path_axes.legend(loc="upper right")
    path_axes.set_title(f"{args.out}: source {args.source}, run {args.run} ({rows[-1][2]:.1f} s)")
    energy_axes.plot(distance, [r[4] for r in rows], color="tab:orange")
    energy_axes.set_ylabel("kinetic energy (kJ)")
    speed_axes = energy_axes.twinx()
    speed_axes.plot(distance, [r[3] for r in rows], color="tab:blue", linewidth=0.8)
    speed_axes.set_ylabel("speed (m/s)", color="tab:blue")
    jump_axes.plot(distance, [r[5] for r in rows], color="tab:green")
    jump_axes.set_ylabel("jump height (m)")
    jump_axes.set_xlabel("horizontal distance along the path (m)")
    for axes in (path_axes, energy_axes, jump_axes):
        axes.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(args.png, dpi=100)
    print(f"wrote {args.png}: {len(rows)} vertices over {distance[-1]:.1f} m")


if __name__ == "__main__":
    main()
