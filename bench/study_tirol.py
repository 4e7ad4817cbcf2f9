#!/usr/bin/python3
"""The regional study benchmark on the whole Tirol DEM (issue 19, "Benchmarks").

Writes a study of data/tirol_alr/avaAlr.tif (417 x 915 cells of 5 m): every cell the
source detection finds (release = "auto", Loye et al. 2009), three block scenarios (0.5 m / 30
years, 1 m / 100 years, 2 m / 300 years), RUNS runs per source, no QGIS project; runs
`talus study` under /usr/bin/time, in one process or under `mpirun -np RANKS` (issue 19, item 6),
and prints one Markdown row per layout (MPI ranks x threads per rank): wall time, peak memory
(resident, of the largest process), trajectories, trajectories per second of simulation, the
study's simulation time, and whether every layer equals the first layout's bit for bit.

A layout may add tiles (issue 19, item 4; docs/study.md, "Tiles"): "1x2:t100" forces tiles of 100
cells, "1x2:m0.45" gives --memory 0.45 (GB). With --mosaic the DEM is the Tirol DEM mirrored into
a 2 x 2 mosaic (834 x 1830 cells, four times the area, seamless at the mirror lines), written
under the work folder.

Usage (from the repository root; about 1.5 to 3 min per row at 100 runs on 2 cores):
  /usr/bin/python3 bench/study_tirol.py [--talus build/talus] [--runs 100] [--layouts 1x1,1x2,2x1] [--mosaic] [--work DIR]
"""
import argparse
import filecmp
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEM = ROOT / "data" / "tirol_alr" / "avaAlr.tif"
BLOCKS = [("blocks-0.5m", "0.5", 30), ("blocks-1m", "1", 100), ("blocks-2m", "2", 300)]


def study_text(runs, dem):
    text = f'[inputs]\ndem = "{dem}"\n'
    for name, size, period in BLOCKS:
        text += (f'\n[[rockfall]]\nname = "{name}"\nrelease = "auto"\nreturn_period = {period}\n'
                 f'[rockfall.run]\nruns = {runs}\n[rockfall.fast_bounce]\nmax_time = 900\n'
                 f'[rockfall.rock]\nsize = "{size}"\n[rockfall.tiles]\nhalo = 2000\n'
                 f'[rockfall.outputs]\nproject = "off"\n')
    return text


def mirrored_mosaic(path):
    """The Tirol DEM and its mirror images, 2 x 2, as one GeoTIFF at `path`."""
    from osgeo import gdal
    import numpy
    source = gdal.Open(str(DEM))
    band = source.GetRasterBand(1)
    a = band.ReadAsArray()
    mosaic = numpy.block([[a, a[:, ::-1]], [a[::-1, :], a[::-1, ::-1]]])
    out = gdal.GetDriverByName("GTiff").Create(str(path), mosaic.shape[1], mosaic.shape[0], 1, band.DataType,
                                               ["COMPRESS=DEFLATE", "TILED=YES"])
    out.SetGeoTransform(source.GetGeoTransform())
    out.SetProjection(source.GetProjection())
    out_band = out.GetRasterBand(1)
    if band.GetNoDataValue() is not None:
        out_band.SetNoDataValue(band.GetNoDataValue())
    out_band.WriteArray(mosaic)
    out = None


def same_layers(a, b):
    """Every .tif under a has a byte-identical twin under b."""
    tifs = sorted(p.relative_to(a) for p in a.rglob("*.tif"))
    return bool(tifs) and all((b / t).exists() and filecmp.cmp(a / t, b / t, shallow=False) for t in tifs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--talus", default=str(ROOT / "build" / "talus"))
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--layouts", default="1x1,1x2,2x1", help="MPI ranks x threads per rank, comma-separated")
    parser.add_argument("--mosaic", action="store_true", help="the 2 x 2 mirrored mosaic of the DEM")
    parser.add_argument("--work", default="")
    args = parser.parse_args()
    work = pathlib.Path(args.work or tempfile.mkdtemp(prefix="talus-study-bench-"))
    work.mkdir(parents=True, exist_ok=True)
    study = work / "tirol.study.toml"
    dem = DEM
    if args.mosaic:
        dem = work / "tirol-mosaic.tif"
        mirrored_mosaic(dem)
    study.write_text(study_text(args.runs, dem))
    print("| MPI ranks x threads | tiles | wall time (s) | peak memory (MB) | sources per scenario | trajectories | "
          "trajectories per second of simulation | simulation (s) | layers as the first row |")
    print("|---|---|---|---|---|---|---|---|---|")
    first = None
    for layout in args.layouts.split(","):
        workers, _, tiling = layout.partition(":")
        ranks, threads = (int(n) for n in workers.split("x"))
        if tiling and tiling[0] == "t":
            # Forced tile sizes are a scenario key: [rockfall.tiles] size.
            study.write_text(study_text(args.runs, dem).replace("[rockfall.tiles]\n",
                                                                f"[rockfall.tiles]\nsize = {tiling[1:]}\n"))
        else:
            study.write_text(study_text(args.runs, dem))
        extra = ["--memory", tiling[1:]] if tiling and tiling[0] == "m" else []
        out = work / f"out-{layout}"
        subprocess.run(["rm", "-rf", str(out)], check=True)
        launcher = [] if ranks == 1 else ["mpirun", "--oversubscribe", "-np", str(ranks)] + (
            ["--allow-run-as-root"] if os.geteuid() == 0 else [])
        timed = subprocess.run(["/usr/bin/time", "-v"] + launcher + [args.talus, "study", str(study), "--out", str(out),
                                "--threads", str(threads), "--project", "off"] + extra,
                               capture_output=True, text=True)
        if timed.returncode != 0:
            sys.exit(f"talus study failed:\n{timed.stdout}\n{timed.stderr}")
        wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", timed.stderr)
        hours, minutes, seconds = (float(g) if g else 0.0 for g in wall.groups())
        peak_mb = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", timed.stderr).group(1)) / 1024
        record = json.loads((out / "study.json").read_text())
        trajectories = sum(s["counts"]["trajectories"] for s in record["scenarios"])
        simulate = sum(s["timings_s"]["simulate"] for s in record["scenarios"])
        sources = record["sources"][BLOCKS[0][0]]["cells"]
        same = "-" if first is None else ("yes" if same_layers(first, out) else "**no**")
        first = first or out
        tiles = [s["tiles"] for s in record["scenarios"] if s.get("tiles")]
        tiling_text = f"{tiles[0]['tiles']} of {tiles[0]['tile_cells']} cells" if tiles else "none"
        print(f"| {ranks} x {threads} | {tiling_text} | {3600 * hours + 60 * minutes + seconds:.1f} | {peak_mb:.0f} | {sources} | "
              f"{trajectories} | {trajectories / simulate:.0f} | {simulate:.1f} | {same} |")


if __name__ == "__main__":
    main()
