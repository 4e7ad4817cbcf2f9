#!/usr/bin/python3
"""The avaAlr comparison with com1DFA over particle size, internal viscosity and seed (issue 20).

Runs `talus mudflow` on AvaFrame's avaAlr case (validation/avaalr_com1dfa/) once per particle
size x internal viscosity x seed, with the case's scenario and only `[rheology]
internal_viscosity` (and with --pressure, `[mud] pressure`) changed, then validation/avaalr_com1dfa/compare.py on each run, and prints
one Markdown row per run: affected area against com1DFA's, footprint IoU, runout along the path,
peak thickness and peak velocity (definitions in compare.py and docs/validation.md, "Where the IoU is lost"),
with the wall time of the simulation (s, from run.json) and the simulated time (s).

Usage (from the repository root; about 5-10 s per run at 4-5 m particles, 20-30 s at 2.5 m):
  /usr/bin/python3 bench/avaalr_resolution_sweep.py [--talus build/talus] [--sizes 4,5]
      [--viscosities 14,16,17,18] [--seeds 1,2,3] [--threads 2] [--work DIR]
      [--pressure normal|vertical]
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
CASE = ROOT / "validation" / "avaalr_com1dfa"
DEM = ROOT / "data" / "tirol_alr" / "avaAlr.tif"
FIGURES = {  # compare.py's row label -> column name here
    "affected area, peak thickness > 0.1 m (km2)": "area",
    "footprint IoU": "iou",
    "runout along the path (m)": "runout",
    "peak flow thickness (m)": "peak_thickness",
    "peak velocity (m/s)": "peak_velocity",
}


def numbers(text):
    return [float(x) for x in re.split(r"[,\s]+", text.strip()) if x]


def replaced(text, key, value):
    """The scenario text with its one `key = ...` line set to `key = value`."""
    changed, count = re.subn(rf"(?m)^{key} = .*$", f"{key} = {value}", text)
    if count != 1:
        sys.exit(f"{CASE / 'scenario.toml'}: expected one {key} line, found {count}")
    return changed


def scenario_with(viscosity, pressure, path):
    """The case's scenario with its internal viscosity (m2/s) and, if given, its pressure column."""
    text = replaced((CASE / "scenario.toml").read_text(), "internal_viscosity", f"{viscosity:g}")
    if pressure:
        text = replaced(text, "pressure", f'"{pressure}"')
    path.write_text(text)


def comparison(out):
    """compare.py's figures for one run: {column: (Talus value, difference text)}."""
    table = subprocess.run([sys.executable, str(CASE / "compare.py"), str(out)], check=True, capture_output=True,
                           text=True).stdout
    figures = {}
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 4 and cells[0] in FIGURES:
            figures[FIGURES[cells[0]]] = (cells[2], cells[3])
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--talus", type=pathlib.Path, default=ROOT / "build" / "talus")
    parser.add_argument("--sizes", default="4,5", help="particle sizes (m)")
    parser.add_argument("--viscosities", default="14,16,17,18", help="internal viscosities (m2/s)")
    parser.add_argument("--seeds", default="1,2,3")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--work", type=pathlib.Path, default=ROOT / "build" / "avaalr-resolution-sweep")
    parser.add_argument("--pressure", choices=["normal", "vertical"],
                        help="[mud] pressure (docs/mudflow.md section 4); default: the case's scenario's")
    args = parser.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)

    print("| particle size (m) | internal viscosity (m2/s) | seed | affected area | IoU | runout | peak thickness "
          "| peak velocity | simulated (s) | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for size in numbers(args.sizes):
        for viscosity in numbers(args.viscosities):
            scenario = args.work / f"scenario_nu{viscosity:g}.toml"
            scenario_with(viscosity, args.pressure, scenario)
            for seed in (int(s) for s in numbers(args.seeds)):
                out = args.work / f"size{size:g}_nu{viscosity:g}_seed{seed}"
                subprocess.run([str(args.talus), "mudflow", "--dem", str(DEM), "--release", str(CASE / "release.vrt"),
                                "--scenario", str(scenario), "--particle-size", f"{size:g}", "--seed", str(seed),
                                "--threads", str(args.threads), "--project", "off", "--out", str(out)],
                               check=True, capture_output=True, text=True)
                record = json.loads((out / "run.json").read_text())
                f = comparison(out)
                print(f"| {size:g} | {viscosity:g} | {seed} | {f['area'][1]} | {f['iou'][0]} | {f['runout'][1]} "
                      f"| {f['peak_thickness'][1]} | {f['peak_velocity'][1]} | {record['end']['simulated_time_s']:.1f} "
                      f"| {record['timings_s']['simulate']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
