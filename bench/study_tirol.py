#!/usr/bin/python3
"""The regional study benchmark on the whole Tirol DEM (issue 19, "Benchmarks").

Writes a study of ../shared/data/tirol_alr/avaAlr.tif (417 x 915 cells of 5 m): every cell the
source detection finds (release = "auto", Loye et al. 2009), three block scenarios (0.5 m / 30
years, 1 m / 100 years, 2 m / 300 years), RUNS runs per source, no QGIS project; runs
`talus study` under /usr/bin/time, in one process or under `mpirun -np RANKS` (issue 19, item 6),
and prints one Markdown row per layout (MPI ranks x threads per rank): wall time, peak memory
(resident, of the largest process), trajectories, trajectories per second of simulation, the
study's simulation time, and whether every layer equals the first layout's bit for bit.

Usage (from the repository root; about 1.5 to 3 min per row at 100 runs on 2 cores):
  /usr/bin/python3 bench/study_tirol.py [--talus build/talus] [--runs 100] [--layouts 1x1,1x2,2x1] [--work DIR]
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
DEM = ROOT.parent / "shared" / "data" / "tirol_alr" / "avaAlr.tif"
BLOCKS = [("blocks-0.5m", "0.5", 30), ("blocks-1m", "1", 100), ("blocks-2m", "2", 300)]


def study_text(runs):
    text = f'[inputs]\ndem = "{DEM}"\n'
    for name, size, period in BLOCKS:
        text += (f'\n[[rockfall]]\nname = "{name}"\nrelease = "auto"\nreturn_period = {period}\n'
                 f'[rockfall.run]\nruns = {runs}\n[rockfall.fast_bounce]\nmax_time = 900\n'
                 f'[rockfall.rock]\nsize = "{size}"\n[rockfall.outputs]\nproject = "off"\n')
    return text


def same_layers(a, b):
    """Every .tif under a has a byte-identical twin under b."""
    tifs = sorted(p.relative_to(a) for p in a.rglob("*.tif"))
    return bool(tifs) and all((b / t).exists() and filecmp.cmp(a / t, b / t, shallow=False) for t in tifs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--talus", default=str(ROOT / "build" / "talus"))
    parser.add_argument("--runs", type=int, default=100)
    parser.add_argument("--layouts", default="1x1,1x2,2x1", help="MPI ranks x threads per rank, comma-separated")
    parser.add_argument("--work", default="")
    args = parser.parse_args()
    work = pathlib.Path(args.work or tempfile.mkdtemp(prefix="talus-study-bench-"))
    work.mkdir(parents=True, exist_ok=True)
    study = work / "tirol.study.toml"
    study.write_text(study_text(args.runs))
    print("| MPI ranks x threads | wall time (s) | peak memory (MB) | sources per scenario | trajectories | "
          "trajectories per second of simulation | simulation (s) | layers as the first row |")
    print("|---|---|---|---|---|---|---|---|")
    first = None
    for layout in args.layouts.split(","):
        ranks, threads = (int(n) for n in layout.split("x"))
        out = work / f"out-{layout}"
        subprocess.run(["rm", "-rf", str(out)], check=True)
        launcher = [] if ranks == 1 else ["mpirun", "--oversubscribe", "-np", str(ranks)] + (
            ["--allow-run-as-root"] if os.geteuid() == 0 else [])
        timed = subprocess.run(["/usr/bin/time", "-v"] + launcher + [args.talus, "study", str(study), "--out", str(out),
                                "--threads", str(threads), "--project", "off"],
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
        print(f"| {ranks} x {threads} | {3600 * hours + 60 * minutes + seconds:.1f} | {peak_mb:.0f} | {sources} | "
              f"{trajectories} | {trajectories / simulate:.0f} | {simulate:.1f} | {same} |")


if __name__ == "__main__":
    main()
