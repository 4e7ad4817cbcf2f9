#!/usr/bin/python3
"""Talus mud flow against the empirical laws of debris-flow mobility (README.md beside this file).

Usage:
  empirical_laws.py [--talus build/talus] [--out out/empirical-laws] [--docs docs]
                    [--sites A,B] [--volumes 100,1000] [--threads N] [--measure-only]
                    [--material NAME] [--coarsen 2]
  empirical_laws.py --choose-sites DEM  (rewrites that DEM's rows of releases.csv; not needed to rerun)

For every release of releases.csv (site, volume) it writes the release as a depth raster on the
DEM's grid, runs `talus mudflow` on that DEM with scenario.toml (and --material) and the
release's particle size, and measures from run.json and flow_depth_max.tif: the released volume V, the drop height
H, the travel distance L along the path, H / L and the inundated planimetric area B. It compares
them with Rickenmann (1999), Corominas (1996) and LAHARZ (Griswold and Iverson 2008) and writes
OUT/results.csv, OUT/summary.json and OUT/empirical-laws.png; with --docs DIR it also copies the
CSV and the chart to DIR/mudflow-empirical-laws[-MATERIAL].csv and .png.
"""
import argparse
import csv
import heapq
import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np
from osgeo import gdal
from scipy import ndimage

gdal.UseExceptions()
gdal.SetConfigOption("GDAL_PAM_ENABLED", "NO")  # no .aux.xml beside the DEM in data/

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
# The terrains, by the short name releases.csv gives in its `dem` column, with the rules that
# choose their sites (README.md, "Method"): the lowest elevation of a site, how far its
# steepest-descent path is followed for the distance to the DEM's edge, and the sites' names.
DEMS = {
    "alr": {"path": os.path.join(ROOT, "data", "tirol_alr", "avaAlr.tif"),
            "min_elevation_m": 1600.0, "path_m": 3500.0, "sites": "ABC"},
    "hit": {"path": os.path.join(ROOT, "data", "avaframe_gar_hit_com1dfa", "avaHit", "dem.tif"),
            "min_elevation_m": 1900.0, "path_m": 1500.0, "sites": "DE"},
    "gar": {"path": os.path.join(ROOT, "data", "avaframe_gar_hit_com1dfa", "avaGar", "dem.tif"),
            "min_elevation_m": 1700.0, "path_m": 1500.0, "sites": "FG"},
}
RELEASES = os.path.join(HERE, "releases.csv")
SCENARIO = os.path.join(HERE, "scenario.toml")

# Thresholds and rules (README.md, "Method").
THRESHOLD_M = 0.1                 # a cell is inundated where flow_depth_max exceeds this
FLOOR_SHARE = 0.05                # the DEM's floor: its lowest 5% of relief (README.md, "Method")
SENSITIVITY_THRESHOLD_M = 0.5     # B is also given at this threshold (not compared with a law)
NOMINAL_DEPTH_M = {100: 1.0, 1000: 1.5, 10000: 2.0, 100000: 3.0, 1000000: 5.0}
TARGET_PARTICLES = 2000           # release cells x cell area / particle_size^2
SITE_SLOPE_DEG = (25.0, 40.0)
SITE_MIN_ACCUMULATION = 400       # D8 contributing cells (1 ha on the 5 m grid)
SITE_SPACING_M = 400.0

# The laws and the bands that define "inside" (README.md, "Laws and bands").
RICKENMANN = {"coef": 1.9, "exp_v": 0.16, "exp_h": 0.83, "upper": 5.0}
RICKENMANN["lower"] = RICKENMANN["coef"] ** 2 / RICKENMANN["upper"]  # mirror of the envelope (ours)
COROMINAS = {"a": -0.012, "b": -0.105, "cl": 0.386}   # debris flows, all paths; 95% limit (log10)
LAHARZ = {"coef": 20.0, "lower": 2.0, "upper": 200.0}  # B = 20 V^(2/3); band ours (README.md)


def read_dem(name):
    data = gdal.Open(DEMS[name]["path"])
    band = data.GetRasterBand(1)
    z = band.ReadAsArray().astype(np.float64)
    valid = z != band.GetNoDataValue()
    return z, valid, data.GetGeoTransform(), data.GetProjection()


def cell_centres(transform, shape):
    rows, cols = np.indices(shape)
    return transform[0] + (cols + 0.5) * transform[1], transform[3] + (rows + 0.5) * transform[5]


def release_cells(x, y, radius, transform, shape):
    """The release: every cell whose centre lies within `radius` of (x, y)."""
    cx, cy = cell_centres(transform, shape)
    return np.hypot(cx - x, cy - y) <= radius


# ---------------------------------------------------------------------------------------------
# Choosing the sites (run once; the result is releases.csv)

def filled(z, valid):
    """Priority-flood pit filling (Barnes et al. 2014) with a 1e-4 m rise per cell, for D8 routing."""
    f = np.where(valid, z, np.inf)
    done = ~valid
    heap = []
    ny, nx = z.shape
    padded = np.pad(valid, 1, constant_values=False)
    interior = np.ones_like(valid)
    for dr in (-1, 0, 1):
        for dc in (-1, 0, 1):
            interior &= padded[1 + dr:1 + dr + ny, 1 + dc:1 + dc + nx]
    for r, c in zip(*np.nonzero(valid & ~interior)):
        heapq.heappush(heap, (f[r, c], r, c))
        done[r, c] = True
    while heap:
        level, r, c = heapq.heappop(heap)
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                rr, cc = r + dr, c + dc
                if 0 <= rr < ny and 0 <= cc < nx and not done[rr, cc]:
                    done[rr, cc] = True
                    f[rr, cc] = max(f[rr, cc], level + 1e-4)
                    heapq.heappush(heap, (f[rr, cc], rr, cc))
    return f


def d8_routing(f, valid):
    """Steepest-descent (D8) receiver of every cell of the filled DEM (-1: none) and the number of
    cells draining through each (itself included)."""
    ny, nx = f.shape
    accumulation = valid.astype(np.float64).ravel()
    receiver = np.full(ny * nx, -1)
    for index in np.argsort(-np.where(valid, f, -np.inf), axis=None):
        r, c = divmod(int(index), nx)
        if not valid[r, c]:
            continue
        best, steepest = -1, 0.0
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                rr, cc = r + dr, c + dc
                if (dr or dc) and 0 <= rr < ny and 0 <= cc < nx and valid[rr, cc]:
                    drop = (f[r, c] - f[rr, cc]) / math.hypot(dr, dc)
                    if drop > steepest:
                        best, steepest = rr * nx + cc, drop
        receiver[index] = best
        if best >= 0:
            accumulation[best] += accumulation[index]
    return receiver, accumulation.reshape(f.shape)


def containment(index, receiver, edge_distance, cell, path_m):
    """The least distance to the DEM's edge along the first path_m of the steepest-descent path
    from a cell (0 where the path leaves the DEM sooner)."""
    length, least = 0.0, edge_distance.flat[index]
    while length < path_m:
        following = receiver[index]
        if following < 0:
            return 0.0
        (r0, c0), (r1, c1) = (divmod(int(i), edge_distance.shape[1]) for i in (index, following))
        length += cell * math.hypot(r1 - r0, c1 - c0)
        index = following
        least = min(least, edge_distance.flat[index])
    return least


def choose_sites(name):
    """Chooses the sites of one DEM and rewrites its rows of releases.csv (the others are kept)."""
    rules = DEMS[name]
    z, valid, transform, _ = read_dem(name)
    cell = transform[1]
    gy, gx = np.gradient(np.where(valid, z, np.nan), cell)
    slope = np.degrees(np.arctan(np.hypot(gx, gy)))
    receiver, accumulation = d8_routing(filled(z, valid), valid)
    edge_distance = ndimage.distance_transform_edt(np.pad(valid, 1))[1:-1, 1:-1] * cell
    cx, cy = cell_centres(transform, z.shape)
    largest = max(NOMINAL_DEPTH_M)
    room = math.sqrt(largest / (math.pi * NOMINAL_DEPTH_M[largest])) + 2 * cell
    candidate = (valid & (slope >= SITE_SLOPE_DEG[0]) & (slope <= SITE_SLOPE_DEG[1]) &
                 (accumulation >= SITE_MIN_ACCUMULATION) & (z >= rules["min_elevation_m"]))
    ranked = []
    for r, c in zip(*np.nonzero(candidate)):
        if valid[release_cells(cx[r, c], cy[r, c], room, transform, z.shape)].all():  # the largest release fits
            ranked.append((-containment(r * z.shape[1] + c, receiver, edge_distance, cell, rules["path_m"]),
                           -accumulation[r, c], r, c))
    chosen = []
    for _, _, r, c in sorted(ranked):
        if len(chosen) < len(rules["sites"]) and all(math.hypot(cx[r, c] - s[0], cy[r, c] - s[1]) >= SITE_SPACING_M for s in chosen):
            chosen.append((cx[r, c], cy[r, c], z[r, c], slope[r, c], accumulation[r, c]))
    kept = [row for row in releases() if row["dem"] != name] if os.path.exists(RELEASES) else []
    rows = []
    for site, (x, y, zs, s, a) in zip(rules["sites"], chosen):
        for volume, depth in sorted(NOMINAL_DEPTH_M.items()):
            radius = math.sqrt(volume / (math.pi * depth))
            cells = int(release_cells(x, y, radius, transform, z.shape).sum())
            size = float("%.2g" % math.sqrt(cells * cell * cell / TARGET_PARTICLES))
            rows.append(dict(zip(RELEASE_COLUMNS, [name, site, "%.4f" % x, "%.4f" % y, "%.1f" % zs, "%.1f" % s, int(a),
                                                   volume, "%.2f" % radius, cells,
                                                   "%.6g" % (volume / (cells * cell * cell)), size])))
    with open(RELEASES, "w", newline="") as f:
        out = csv.DictWriter(f, RELEASE_COLUMNS, lineterminator="\n")
        out.writeheader()
        out.writerows(sorted(kept + rows, key=lambda row: (row["site"], int(row["volume_m3"]))))
    print("wrote %s: %d sites on %s" % (RELEASES, len(chosen), name))


# ---------------------------------------------------------------------------------------------
# Running and measuring

RELEASE_COLUMNS = ["dem", "site", "x", "y", "site_z_m", "site_slope_deg", "site_accumulation_cells", "volume_m3",
                   "radius_m", "cells", "depth_m", "particle_size_m"]


def releases(sites=None, volumes=None):
    with open(RELEASES) as f:
        rows = list(csv.DictReader(f))
    return [row for row in rows if (not sites or row["site"] in sites) and
            (not volumes or int(row["volume_m3"]) in volumes)]


def write_release(row, path, dem):
    z, valid, transform, projection = dem
    cells = release_cells(float(row["x"]), float(row["y"]), float(row["radius_m"]), transform, z.shape)
    data = gdal.GetDriverByName("GTiff").Create(path, z.shape[1], z.shape[0], 1, gdal.GDT_Float32,
                                                ["COMPRESS=DEFLATE"])
    data.SetGeoTransform(transform)
    data.SetProjection(projection)
    data.GetRasterBand(1).WriteArray(np.where(cells, float(row["depth_m"]), 0.0).astype(np.float32))
    data = None
    return cells


def path_distances(passable, start, cell):
    """Horizontal distance from `start` to every cell along the shortest path through `passable`
    cells, with the 16 moves of a chess king and knight (at most 2.7% longer than straight)."""
    moves = [(dr, dc, cell * math.hypot(dr, dc)) for dr in range(-2, 3) for dc in range(-2, 3)
             if (dr or dc) and abs(dr) + abs(dc) <= 3 and math.gcd(abs(dr), abs(dc)) == 1]
    distance = np.full(passable.shape, np.inf)
    distance[start] = 0.0
    heap = [(0.0, start[0], start[1])]
    ny, nx = passable.shape
    while heap:
        d, r, c = heapq.heappop(heap)
        if d > distance[r, c]:
            continue
        for dr, dc, step in moves:
            rr, cc = r + dr, c + dc
            if 0 <= rr < ny and 0 <= cc < nx and passable[rr, cc] and d + step < distance[rr, cc]:
                distance[rr, cc] = d + step
                heapq.heappush(heap, (d + step, rr, cc))
    return distance


def measure(row, folder, dem, release):
    """V, H, L, B of one run (README.md, "Method")."""
    z, valid, transform, _ = dem
    cell = transform[1]
    with open(os.path.join(folder, "run.json")) as f:
        run = json.load(f)
    depth = gdal.Open(os.path.join(folder, "flow_depth_max.tif")).ReadAsArray().astype(np.float64)
    inundated = valid & (depth > THRESHOLD_M)
    top = np.unravel_index(np.argmax(np.where(release, z, -np.inf)), z.shape)
    along = path_distances((valid & (depth > 0.0)) | release, top, cell)  # the path the mud took
    reached = inundated & np.isfinite(along)
    cx, cy = cell_centres(transform, z.shape)
    straight = np.hypot(cx - cx[top], cy - cy[top])
    volume = run["volumes_m3"]["released"]
    result = {
        "dem": row["dem"], "site": row["site"], "volume_nominal_m3": int(row["volume_m3"]), "volume_m3": volume,
        "depth_m": float(row["depth_m"]), "particle_size_m": run["parameters"]["mud"]["particle_size"],
        "release_area_m2": release.sum() * cell * cell,
        "H_m": z[top] - z[reached].min(),
        "L_m": along[reached].max(), "L_straight_m": straight[reached].max(),
        "B_m2": (reached & ~release).sum() * cell * cell, "B_total_m2": inundated.sum() * cell * cell,
        "B_unconnected_m2": (inundated & ~reached).sum() * cell * cell,
        "B_05_m2": (reached & ~release & (depth > SENSITIVITY_THRESHOLD_M)).sum() * cell * cell,
        "above_floor_m": z[reached].min() - z[valid].min(),
        "floor_m": FLOOR_SHARE * (z[valid].max() - z[valid].min()),
        "outflow_m3": run["volumes_m3"]["outflow"], "end_reason": run["end"]["reason"],
        "simulated_s": run["end"]["simulated_time_s"], "particles_initial": run["counts"]["particles"]["initial"],
        "particle_steps": run["counts"]["particle_steps"],
    }
    result["H_over_L"] = result["H_m"] / result["L_m"]
    return result


def left_dem(result):
    """Whether more than 1% of the released mud left the DEM."""
    return result["outflow_m3"] > 0.01 * result["volume_m3"]


def reached_floor(result):
    """Whether the mud reached the DEM's floor (its lowest inundated cell lies in the lowest
    FLOOR_SHARE of the DEM's relief): the drop H cannot grow further on this DEM."""
    return result["above_floor_m"] < result["floor_m"]


def censored(result):
    """Whether the DEM, not the flow, bounds L, H and B: the mud left it or reached its floor."""
    return left_dem(result) or reached_floor(result)


def compare(result):
    """Each law's prediction, the simulated value over it, and whether it lies inside the band."""
    v, h = result["volume_m3"], result["H_m"]
    r = RICKENMANN
    result["L_rickenmann_m"] = r["coef"] * v ** r["exp_v"] * h ** r["exp_h"]
    result["L_ratio"] = result["L_m"] / result["L_rickenmann_m"]
    result["L_inside"] = r["lower"] / r["coef"] <= result["L_ratio"] <= r["upper"] / r["coef"]
    c = COROMINAS
    result["HL_corominas"] = 10 ** (c["a"] + c["b"] * math.log10(v))
    result["HL_ratio"] = result["H_over_L"] / result["HL_corominas"]
    result["HL_inside"] = abs(math.log10(result["HL_ratio"])) <= c["cl"]
    result["B_laharz_m2"] = LAHARZ["coef"] * v ** (2.0 / 3.0)
    result["B_ratio"] = result["B_m2"] / result["B_laharz_m2"]
    result["B_inside"] = LAHARZ["lower"] / LAHARZ["coef"] <= result["B_ratio"] <= LAHARZ["upper"] / LAHARZ["coef"]
    result["left_dem"] = left_dem(result)
    result["reached_floor"] = reached_floor(result)
    return result


COLUMNS = ["dem", "site", "volume_nominal_m3", "volume_m3", "depth_m", "particle_size_m", "release_area_m2", "H_m", "L_m",
           "L_straight_m", "H_over_L", "B_m2", "B_total_m2", "B_unconnected_m2", "B_05_m2", "L_rickenmann_m", "L_ratio",
           "L_inside", "HL_corominas", "HL_ratio", "HL_inside", "B_laharz_m2", "B_ratio", "B_inside",
           "outflow_m3", "left_dem", "above_floor_m", "floor_m", "reached_floor", "end_reason", "simulated_s", "wall_s", "particles_initial", "particle_steps"]


def write_csv(results, path):
    with open(path, "w", newline="") as f:
        out = csv.DictWriter(f, COLUMNS, extrasaction="ignore", lineterminator="\n")
        out.writeheader()
        for r in results:
            out.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})


def chart(results, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    markers = dict(zip("ABCDEFGH", "osD^v<>p"))
    colours = {100: "#440154", 1000: "#3b528b", 10000: "#21918c", 100000: "#5ec962", 1000000: "#fde725"}
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    v = np.logspace(1.5, 6.5, 50)

    def point(ax, r, x, y):  # a run the DEM bounds has a red edge: its L, H and B are bounds, not values
        ax.plot(x, y, markers[r["site"]], color=colours[r["volume_nominal_m3"]], ms=7,
                mec="r" if censored(r) else "k", mew=1.6 if censored(r) else 1.0)

    ax = axes[0]
    predicted = np.array([r["L_rickenmann_m"] for r in results])
    x = np.logspace(np.log10(predicted.min() / 3), np.log10(predicted.max() * 3), 50)
    ax.fill_between(x, x * RICKENMANN["lower"] / RICKENMANN["coef"], x * RICKENMANN["upper"] / RICKENMANN["coef"],
                    color="0.9", label="band: envelope 5.0 and its mirror 0.72")
    ax.plot(x, x, "k-", label="L = 1.9 V^0.16 H^0.83")
    ax.plot(x, x * RICKENMANN["upper"] / RICKENMANN["coef"], "k--", lw=0.8, label="envelope L = 5.0 V^0.16 H^0.83")
    for r in results:
        point(ax, r, r["L_rickenmann_m"], r["L_m"])
    ax.set(xscale="log", yscale="log", xlabel="Rickenmann (1999): 1.9 V^0.16 H^0.83 (m)",
           ylabel="simulated L along the path (m)", title="Travel distance (Rickenmann 1999)")

    ax = axes[1]
    fit = 10 ** (COROMINAS["a"] + COROMINAS["b"] * np.log10(v))
    ax.fill_between(v, fit / 10 ** COROMINAS["cl"], fit * 10 ** COROMINAS["cl"], color="0.9",
                    label="95% limit, +-0.386 in log10")
    ax.plot(v, fit, "k-", label="log(H/L) = -0.105 log V - 0.012")
    for r in results:
        point(ax, r, r["volume_m3"], r["H_over_L"])
    slope = corominas_slope(results)
    kept = [r for r in results if not censored(r)]
    if math.isfinite(slope):
        x = np.log10([r["volume_m3"] for r in kept])
        y = np.log10([r["H_over_L"] for r in kept])
        ax.plot(v, 10 ** (y.mean() + slope * (np.log10(v) - x.mean())), "b--", lw=1,
                label="fit to the runs the DEM does not bound: slope %.3f" % slope)
    ax.set(xscale="log", yscale="log", xlabel="V (m3)", ylabel="H / L", title="Angle of reach (Corominas 1996)")

    ax = axes[2]
    ax.fill_between(v, LAHARZ["lower"] * v ** (2 / 3), LAHARZ["upper"] * v ** (2 / 3), color="0.9",
                    label="band: 2 to 200 V^(2/3) (ours)")
    ax.plot(v, LAHARZ["coef"] * v ** (2 / 3), "k-", label="B = 20 V^(2/3)")
    for r in results:
        point(ax, r, r["volume_m3"], r["B_m2"])
        ax.plot(r["volume_m3"] * 1.25, r["B_05_m2"], markers[r["site"]], mfc="none", mec="0.4", ms=4)
    ax.set(xscale="log", yscale="log", xlabel="V (m3)", ylabel="B (m2)",
           title="Inundated area (LAHARZ; Griswold & Iverson 2008)")
    for ax in axes:
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7, loc="best")
    handles = [plt.Line2D([], [], ls="", marker=m, color="w", mec="k", label="site " + s) for s, m in markers.items()
               if any(r["site"] == s for r in results)]
    handles += [plt.Line2D([], [], ls="", marker="o", color=c, mec="k", label="10^%d m3" % round(math.log10(v)))
                for v, c in colours.items()]
    handles.append(plt.Line2D([], [], ls="", marker="o", color="w", mec="r", mew=1.6,
                              label="bounded by the DEM (left it or reached its floor)"))
    handles.append(plt.Line2D([], [], ls="", marker="o", mfc="none", mec="0.4", ms=4, label="B at 0.5 m (beside)"))
    fig.legend(handles=handles, loc="lower center", ncol=(len(handles) + 1) // 2, fontsize=8, frameon=False)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.1, 1, 0.96))
    fig.savefig(path, dpi=110)


def corominas_slope(results):
    """The least-squares slope of log10(H/L) on log10(V) over the runs the DEM does not bound
    (NaN with fewer than two volumes)."""
    kept = [r for r in results if not censored(r)]
    if len({r["volume_nominal_m3"] for r in kept}) < 2:
        return float("nan")
    x = np.log10([r["volume_m3"] for r in kept])
    y = np.log10([r["H_over_L"] for r in kept])
    return float(np.polyfit(x, y, 1)[0])


def summary(results, material):
    inside = {law: int(sum(bool(r[key]) for r in results)) for law, key in
              (("rickenmann", "L_inside"), ("corominas", "HL_inside"), ("laharz", "B_inside"))}
    slope = corominas_slope(results)
    return {"material": material or "default", "runs": len(results),
            "runs_not_bounded_by_the_dem": int(sum(not censored(r) for r in results)),
            "inside": inside, "corominas_slope": slope, "corominas_slope_law": COROMINAS["b"],
            "corominas_slope_inside": bool(abs(slope - COROMINAS["b"]) <= 0.5 * abs(COROMINAS["b"])),
            "median_B_ratio": float(np.median([r["B_ratio"] for r in results])),
            "median_L_ratio": float(np.median([r["L_ratio"] for r in results]))}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "empirical-laws"))
    parser.add_argument("--docs", help="also copy the CSV, the summary and the chart into this folder")
    parser.add_argument("--scenario", default=SCENARIO, help="scenario TOML (default: scenario.toml here)")
    parser.add_argument("--material", help="talus --material NAME (default: Talus's default material)")
    parser.add_argument("--voellmy", metavar="MU,XI,TAU_Y",
                        help="run Voellmy with these friction (-), turbulence (m/s2) and yield stress (Pa) instead of "
                             "the material's: the scenario with a [rheology] section added, written to OUT")
    parser.add_argument("--sites", help="comma-separated site names (default: all)")
    parser.add_argument("--volumes", help="comma-separated volumes in m3 (default: all)")
    parser.add_argument("--threads", type=int, default=0, help="talus --threads (0: all cores)")
    parser.add_argument("--coarsen", type=float, default=1.0,
                        help="multiply every particle size by this (the case test uses 2)")
    parser.add_argument("--measure-only", action="store_true", help="measure the runs already in --out")
    parser.add_argument("--choose-sites", metavar="DEM", choices=sorted(DEMS),
                        help="rewrite that DEM's rows of releases.csv from the DEM")
    args = parser.parse_args()
    if args.choose_sites:
        choose_sites(args.choose_sites)
        return
    chosen = releases(args.sites.split(",") if args.sites else None,
                      [int(float(v)) for v in args.volumes.split(",")] if args.volumes else None)
    dems = {name: read_dem(name) for name in sorted({row["dem"] for row in chosen})}
    os.makedirs(args.out, exist_ok=True)
    if args.voellmy:
        friction, turbulence, yield_stress = (float(value) for value in args.voellmy.split(","))
        with open(args.scenario) as f:
            text = f.read()
        args.scenario = os.path.join(args.out, "scenario.toml")
        with open(args.scenario, "w") as f:
            f.write(text + '\n[rheology]\nrheology = "voellmy"\nfriction = %g\nturbulence = %g\nyield_stress = %g\n' %
                    (friction, turbulence, yield_stress))
    results = []
    environment = dict(os.environ, OMP_WAIT_POLICY="passive")
    for row in chosen:
        name = "%s-%s" % (row["site"], row["volume_m3"])
        folder = os.path.join(args.out, name)
        dem = dems[row["dem"]]
        release = write_release(row, os.path.join(args.out, name + "-release.tif"), dem)
        wall = float("nan")
        if not args.measure_only:
            command = [args.talus, "mudflow", "--dem", DEMS[row["dem"]]["path"],
                       "--release", os.path.join(args.out, name + "-release.tif"),
                       "--scenario", args.scenario, "--particle-size", "%g" % (float(row["particle_size_m"]) * args.coarsen),
                       "--threads", str(args.threads), "--out", folder]
            if args.material:
                command += ["--material", args.material]
            start = time.monotonic()
            done = subprocess.run(command, env=environment, capture_output=True, text=True)
            wall = time.monotonic() - start
            if done.returncode != 0:
                sys.exit("%s failed (exit %d):\n%s" % (" ".join(command), done.returncode, done.stderr[-2000:]))
            with open(os.path.join(args.out, name + ".log"), "w") as log:
                log.write(" ".join(command) + "\n" + done.stdout + done.stderr + "wall %.1f s\n" % wall)
        elif os.path.exists(os.path.join(args.out, name + ".log")):
            with open(os.path.join(args.out, name + ".log")) as log:
                wall = float(log.read().rsplit("wall ", 1)[1].split()[0])
        result = compare(measure(row, folder, dem, release))
        result["wall_s"] = wall
        results.append(result)
        print("%-10s V %9.0f m3  H %6.1f m  L %7.1f m  H/L %.3f  B %9.0f m2  | L/L_R %.2f%s  (H/L)/C %.2f%s  "
              "B/B_LZ %.2f%s  | %s, %.0f s of flow, %.1f s wall%s" %
              (name, result["volume_m3"], result["H_m"], result["L_m"], result["H_over_L"], result["B_m2"],
               result["L_ratio"], "" if result["L_inside"] else "!", result["HL_ratio"],
               "" if result["HL_inside"] else "!", result["B_ratio"], "" if result["B_inside"] else "!",
               result["end_reason"], result["simulated_s"], wall,
               (", %.0f m3 left the DEM" % result["outflow_m3"] if result["left_dem"] else "") +
               (", reached the DEM's floor" if result["reached_floor"] else "")), flush=True)
    totals = summary(results, args.material)
    if args.voellmy:
        totals["voellmy"] = args.voellmy
    write_csv(results, os.path.join(args.out, "results.csv"))
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(totals, f, indent=2)
    chart(results, os.path.join(args.out, "empirical-laws.png"),
          "Talus mud flow, material %s, against the empirical laws of debris flows" % (args.material or "debris-flow (default)"))
    if args.docs:
        stem = "mudflow-empirical-laws" + ("-" + args.material if args.material else "")
        shutil.copy(os.path.join(args.out, "results.csv"), os.path.join(args.docs, stem + ".csv"))
        shutil.copy(os.path.join(args.out, "empirical-laws.png"), os.path.join(args.docs, stem + ".png"))
    for law, key in (("Rickenmann", "rickenmann"), ("Corominas", "corominas"), ("LAHARZ", "laharz")):
        print("%-10s inside its band: %d of %d runs" % (law, totals["inside"][key], len(results)))
    print("Corominas  slope of log10(H/L) on log10(V) over the %d runs the DEM does not bound: %.3f (law %.3f, "
          "+-50%%: %s)" % (totals["runs_not_bounded_by_the_dem"], totals["corominas_slope"], COROMINAS["b"],
           "inside" if totals["corominas_slope_inside"] else "outside"))


if __name__ == "__main__":
    main()
