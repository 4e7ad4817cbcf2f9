#!/usr/bin/python3
"""Talus's mud-flow layers on avaAlr, avaGar or avaHit against AvaFrame com1DFA's peak fields.

Usage: compare.py TALUS_OUT [--case avaAlr|avaGar|avaHit] [--png DIR] [--data DIR]

TALUS_OUT is the --out folder of (avaAlr, the default case)
  build/talus mudflow --dem data/tirol_alr/avaAlr.tif \
      --release validation/avaalr_com1dfa/release.vrt \
      --scenario validation/avaalr_com1dfa/scenario.toml --out TALUS_OUT
or of the same scenario on another path (CASE avaGar or avaHit, D=data/avaframe_gar_hit_com1dfa/CASE)
  build/talus mudflow --dem $D/dem.tif --release $D/relGar.shp (relHit.shp) --depth-field thickness \
      --scenario validation/avaalr_com1dfa/scenario.toml --out TALUS_OUT
Prints the comparison table of docs/validation.md ("Mud flow: code-to-code (AvaFrame
com1DFA)") as Markdown; with --png, writes the difference maps and a map of the two footprints there.

Definitions (the same as tests/cases/avaalr_com1dfa_test.cpp):
- affected area: cells whose peak flow thickness exceeds 0.1 m (km2);
- footprint IoU: intersection over union of the two affected areas;
- runout along the path: the longest path inside the affected area (and the release) from the
  release's highest cell, over the cell centres with the 16 moves of a chess king and knight
  (tests/support/path_distances.hpp, and empirical_laws.py's path_distances);
- travel angle: atan(drop from the release's highest cell to the farthest cell / runout);
- peak thickness and peak velocity: the maxima of the layers over the affected area.
"""
import argparse
import heapq
import json
import math
import pathlib

import numpy as np
from osgeo import gdal

gdal.UseExceptions()
THRESHOLD = 0.1  # m: affected-area threshold on the peak flow thickness


def read(path):
    dataset = gdal.Open(str(path))  # kept while its band is read
    band = dataset.GetRasterBand(1)
    values = band.ReadAsArray().astype(float)
    nodata = band.GetNoDataValue()
    if nodata is not None:
        values[values == nodata] = 0.0
    values[~np.isfinite(values)] = 0.0
    return np.maximum(values, 0.0)


def steps16():
    """The 16 moves of a chess king and knight, with their lengths in cells."""
    return [(dr, dc, math.hypot(dr, dc))
            for dr in range(-2, 3) for dc in range(-2, 3)
            if (dr, dc) != (0, 0) and math.gcd(abs(dr), abs(dc)) == 1]


def path_distances(inside, start, cell):
    """Shortest distances (m) inside `inside` from `start` over the 16-neighbour steps."""
    rows, cols = inside.shape
    distance = np.full(inside.shape, np.inf)
    distance[start] = 0.0
    queue = [(0.0, start)]
    steps = steps16()
    while queue:
        d, (r, c) = heapq.heappop(queue)
        if d > distance[r, c]:
            continue
        for dr, dc, length in steps:
            rr, cc = r + dr, c + dc
            if not (0 <= rr < rows and 0 <= cc < cols) or not inside[rr, cc]:
                continue
            nd = d + length * cell
            if nd < distance[rr, cc]:
                distance[rr, cc] = nd
                heapq.heappush(queue, (nd, (rr, cc)))
    return distance


def footprint_figures(thickness, velocity, release, z, cell):
    affected = thickness > THRESHOLD
    start = np.unravel_index(np.argmax(np.where(release, z, -np.inf)), z.shape)
    distance = path_distances(affected | release, start, cell)
    distance[~np.isfinite(distance)] = -1.0
    far = np.unravel_index(np.argmax(distance), z.shape)
    runout = float(distance[far])
    return {
        "area_km2": affected.sum() * cell * cell * 1e-6,
        "runout_m": runout,
        "travel_angle_deg": math.degrees(math.atan2(z[start] - z[far], runout)),
        "peak_thickness_m": float(thickness[affected].max()),
        "peak_velocity_ms": float(velocity[affected].max()),
        "affected": affected,
    }


def case_files(case, data):
    """The DEM, the release polygon and com1DFA's peak thickness and velocity of a case, and the
    volume com1DFA released (m3: its released mass over its 200 kg/m3)."""
    if case == "avaAlr":
        reference = data / "avaframe_alr_com1dfa"
        return (data / "tirol_alr" / "avaAlr.tif", pathlib.Path(__file__).with_name("release.vrt"),
                reference / "com1dfa_voellmy_pft.tif", reference / "com1dfa_voellmy_pfv.tif", 52796.0)
    folder = data / "avaframe_gar_hit_com1dfa" / case
    mass = json.loads((folder / "com1dfa.json").read_text())["com1dfa"]["initial_mass_kg"]
    return (folder / "dem.tif", folder / f"rel{case[3:]}.shp", folder / "com1dfa_pft.tif",
            folder / "com1dfa_pfv.tif", mass / 200.0)


def side_channel(shape):
    """The side channel east of the fan's left bank, where the two footprints part most
    (docs/validation.md, point 8): cells at or east of column 115 in rows 400 to 529 of
    avaAlr's 5 m grid."""
    mask = np.zeros(shape, dtype=bool)
    mask[400:530, 115:] = True
    return mask


def shaded_window(mask, z, margin):
    """The window (first row, end row, first column, end column) around the cells of `mask`
    widened by `margin` cells, the slope shading of the 5 m DEM `z` in it and its elevations."""
    rows = np.where(mask.any(axis=1))[0]
    cols = np.where(mask.any(axis=0))[0]
    r0, r1 = max(rows[0] - margin, 0), min(rows[-1] + margin, z.shape[0])
    c0, c1 = max(cols[0] - margin, 0), min(cols[-1] + margin, z.shape[1])
    ground = np.where(z > -1000, z, np.nan)[r0:r1, c0:c1]
    dy, dx = np.gradient(ground, 5.0)
    return (r0, r1, c0, c1), 1.0 - np.hypot(dx, dy) / 2.0, ground


def difference_map(path, title, talus, reference, z, unit, limit):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    either = (talus > 0) | (reference > 0)
    (r0, r1, c0, c1), shade, _ = shaded_window(either, z, 20)
    difference = np.ma.masked_where(~either[r0:r1, c0:c1], (talus - reference)[r0:r1, c0:c1])
    fig, ax = plt.subplots(figsize=(5.5, 8))
    ax.imshow(shade, cmap="gray", vmin=0, vmax=1)
    image = ax.imshow(difference, cmap="RdBu_r", vmin=-limit, vmax=limit)
    ax.set_title(title)
    ax.set_xticks([])
    ax.set_yticks([])
    fig.colorbar(image, ax=ax, shrink=0.6, label=f"Talus - com1DFA ({unit})")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def footprint_map(path, talus, reference, z):
    """The two affected areas (peak thickness > 0.1 m) over the hillshade and 20 m contours, cropped
    to the rows and columns where they differ: cells both reach, com1DFA's only, Talus's only."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    differ = talus ^ reference
    (r0, r1, c0, c1), shade, ground = shaded_window(differ if differ.any() else talus | reference, z, 10)
    classes = np.zeros(z.shape)
    classes[talus & reference] = 1
    classes[reference & ~talus] = 2
    classes[talus & ~reference] = 3
    colours = ["tab:green", "tab:blue", "tab:red"]
    fig, ax = plt.subplots(figsize=(5.5, 8))
    ax.imshow(shade, cmap="gray", vmin=0, vmax=1)
    ax.imshow(np.ma.masked_where(classes == 0, classes)[r0:r1, c0:c1], cmap=ListedColormap(colours), vmin=1, vmax=3,
              alpha=0.6, interpolation="nearest")
    low, high = np.nanmin(ground), np.nanmax(ground)
    ax.contour(ground, levels=np.arange(np.ceil(low / 20) * 20, high, 20.0), colors="k", linewidths=0.2, alpha=0.6)
    ax.set_title("Affected area (peak thickness > 0.1 m)")
    ax.set_xticks([])
    ax.set_yticks([])
    ax.legend(handles=[Patch(color=c, alpha=0.6, label=label) for c, label in
                       zip(colours, ["both", "com1DFA only", "Talus only"])], loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("talus_out", type=pathlib.Path)
    parser.add_argument("--case", choices=["avaAlr", "avaGar", "avaHit"], default="avaAlr")
    parser.add_argument("--png", type=pathlib.Path, help="folder for the difference maps and the footprint map")
    parser.add_argument("--data", type=pathlib.Path,
                        default=pathlib.Path(__file__).resolve().parents[2] / "data",
                        help="the folder of the real data sets (default: the repository's data/)")
    args = parser.parse_args()

    dem_path, release_path, pft_path, pfv_path, com_released = case_files(args.case, args.data)
    dem = gdal.Open(str(dem_path))
    z = dem.ReadAsArray().astype(float)
    cell = dem.GetGeoTransform()[1]
    release_raster = gdal.Rasterize("/vsimem/release.tif", str(release_path),
                             format="GTiff", width=dem.RasterXSize, height=dem.RasterYSize,
                             outputBounds=[dem.GetGeoTransform()[0],
                                           dem.GetGeoTransform()[3] - cell * dem.RasterYSize,
                                           dem.GetGeoTransform()[0] + cell * dem.RasterXSize,
                                           dem.GetGeoTransform()[3]],
                             burnValues=[1], outputType=gdal.GDT_Byte)
    release = release_raster.ReadAsArray() > 0

    com_thickness = read(pft_path)
    com_velocity = read(pfv_path)
    talus_thickness = read(args.talus_out / "flow_depth_max.tif")
    talus_velocity = read(args.talus_out / "velocity_max.tif")
    if talus_thickness.shape != z.shape:
        parser.exit(2, f"compare.py: error: {args.talus_out / 'flow_depth_max.tif'}: {talus_thickness.shape[1]} x "
                       f"{talus_thickness.shape[0]} cells, not {args.case}'s {z.shape[1]} x {z.shape[0]}: not a run "
                       f"on {dem_path.name}\n")
    com = footprint_figures(com_thickness, com_velocity, release, z, cell)
    talus = footprint_figures(talus_thickness, talus_velocity, release, z, cell)
    a, b = com["affected"], talus["affected"]
    iou = (a & b).sum() / (a | b).sum()
    both = a & b
    run = json.loads((args.talus_out / "run.json").read_text())
    released = run.get("volumes_m3", {}).get("released")

    def row(name, key, unit, digits):
        ratio = talus[key] / com[key] - 1.0
        return f"| {name} ({unit}) | {com[key]:.{digits}f} | {talus[key]:.{digits}f} | {ratio:+.1%} |"

    print("| figure | com1DFA | Talus | difference |")
    print("|---|---|---|---|")
    if released is not None:
        print(f"| released volume (m3) | {com_released:.0f} | {released:.0f} | {released / com_released - 1:+.1%} |")
    print(row("affected area, peak thickness > 0.1 m", "area_km2", "km2", 3))
    print(f"| footprint IoU | - | {iou:.3f} | - |")
    print(row("runout along the path", "runout_m", "m", 0))
    print(row("travel angle", "travel_angle_deg", "deg", 2))
    print(row("peak flow thickness", "peak_thickness_m", "m", 2))
    print(row("peak velocity", "peak_velocity_ms", "m/s", 1))
    dh = talus_thickness[both] - com_thickness[both]
    dv = talus_velocity[both] - com_velocity[both]
    print(f"| peak thickness where both reach: mean / RMS difference (m) | - | {dh.mean():+.2f} / {np.sqrt((dh**2).mean()):.2f} | - |")
    print(f"| peak velocity where both reach: mean / RMS difference (m/s) | - | {dv.mean():+.1f} / {np.sqrt((dv**2).mean()):.1f} | - |")
    if args.case == "avaAlr":
        side_only = b & ~a & side_channel(a.shape)
        print(f"| cells reached by Talus only in the side channel (rows 400-529, columns >= 115) | - | {side_only.sum()} | - |")
        print(f"| footprint IoU without them | - | {(a & b).sum() / ((b & ~side_only) | a).sum():.3f} | - |")
    if args.png:
        args.png.mkdir(parents=True, exist_ok=True)
        name = args.case.lower()
        difference_map(args.png / f"{name}-thickness-difference.png", "Peak flow thickness, Talus - com1DFA",
                       talus_thickness, com_thickness, z, "m", 5.0)
        difference_map(args.png / f"{name}-velocity-difference.png", "Peak velocity, Talus - com1DFA",
                       talus_velocity, com_velocity, z, "m/s", 20.0)
        footprint_map(args.png / f"{name}-footprints.png", b, a, z)


if __name__ == "__main__":
    main()
