#!/usr/bin/python3
"""Wall time per simulated second of the mud flow on AvaFrame's three paths, against com1DFA (issue 37, item 3).

Runs `talus mudflow` on avaAlr, avaGar and avaHit with one scenario (by default the avaAlr case's,
validation/avaalr_com1dfa/scenario.toml; --scenario com1dfa_physics.toml for com1DFA's physics)
for each adaptivity setting and thread count, in
rounds that alternate the runs (the machine's noise falls on all of them alike), and prints one
Markdown row per path x setting x thread count with the median over the rounds:

  wall_per_sim_s    wall time of the simulation (run.json timings_s.simulate) per simulated second (s/s)
  vs_com1dfa        com1DFA's computation time on one core over Talus's simulation time (x faster;
                    com1DFA's from the data set's record, com1dfa.json `computation_time_s`: 44.1 s
                    for avaGar, 156.8 s for avaHit, both on a loaded machine; avaAlr's is not recorded)
  steps_per_sim_s   particle-steps per simulated second (millions)
  us_per_step       wall time per particle-step (microseconds): what one particle costs per step
  steps_per_particle  particle-steps over the mean of the initial and peak particle counts
and the run's figures against com1DFA (compare.py --case): area difference and IoU.

Settings: `default` (crowded fusion, one cell per step: docs/mudflow.md section 8),
`paper` (`[adaptivity] crowded_merge = 0`: the paper's fusion alone, half a cell per step),
`uniform` (`--adaptive off`).

Usage (from the repository root; a round of everything takes about 5 minutes on 2 cores):
  /usr/bin/python3 bench/com1dfa_paths_speed.py [--talus build/talus] [--paths avaAlr,avaGar,avaHit]
      [--settings default,paper] [--threads 1,2] [--rounds 3] [--work DIR] [--scenario FILE]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
CASE = ROOT / "validation" / "avaalr_com1dfa"
PATHS = ROOT / "data" / "avaframe_gar_hit_com1dfa"


def com1dfa_seconds(path):
    """com1DFA's computation time on one core (s), or None where the data set does not record it."""
    record = PATHS / path / "com1dfa.json"
    return json.loads(record.read_text())["com1dfa"]["computation_time_s"] if record.exists() else None


def release_arguments(path):
    if path == "avaAlr":
        return ["--dem", str(ROOT / "data" / "tirol_alr" / "avaAlr.tif"), "--release", str(CASE / "release.vrt")]
    folder = PATHS / path
    return ["--dem", str(folder / "dem.tif"), "--release", str(folder / f"rel{path[3:]}.shp"), "--depth-field",
            "thickness"]


def scenario_for(scenario, setting, work):
    """The scenario, with the paper's fusion alone for `paper`."""
    if setting != "paper":
        return scenario
    path = work / "paper_fusion.toml"
    path.write_text(scenario.read_text() + "\n[adaptivity]\ncrowded_merge = 0\n")
    return path


def run(talus, scenario, path, setting, threads, work):
    out = work / f"{path}-{setting}-t{threads}"
    command = [str(talus), "mudflow", *release_arguments(path), "--scenario", str(scenario_for(scenario, setting, work)),
               "--threads", str(threads), "--project", "off", "--out", str(out)]
    if setting == "uniform":
        command += ["--adaptive", "off"]
    subprocess.run(command, check=True, capture_output=True)
    record = json.loads((out / "run.json").read_text())
    counts = record["counts"]
    simulated = record["end"]["simulated_time_s"]
    wall = record["timings_s"]["simulate"]
    particles = 0.5 * (counts["particles"]["initial"] + counts["particles"]["peak"])
    return out, {"wall_per_sim_s": wall / simulated, "wall_s": wall,
                 "steps_per_sim_s": counts["particle_steps"] / simulated / 1e6,
                 "us_per_step": wall / counts["particle_steps"] * 1e6,
                 "steps_per_particle": counts["particle_steps"] / particles}


def figures(path, out):
    """Area difference and IoU against com1DFA, from compare.py's table."""
    table = subprocess.run([sys.executable, str(CASE / "compare.py"), str(out), "--case", path], check=True,
                           capture_output=True, text=True).stdout
    values = {}
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[0].startswith("affected area"):
            values["area"] = cells[3]
        elif cells[0] == "footprint IoU":
            values["iou"] = cells[2]
    return values


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--talus", type=pathlib.Path, default=ROOT / "build" / "talus")
    parser.add_argument("--paths", default="avaAlr,avaGar,avaHit")
    parser.add_argument("--settings", default="default,paper")
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--work", type=pathlib.Path, default=ROOT / "build" / "com1dfa-paths-speed")
    parser.add_argument("--scenario", type=pathlib.Path, default=CASE / "scenario.toml")
    args = parser.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    jobs = [(p, s, int(t)) for p in args.paths.split(",") for s in args.settings.split(",")
            for t in args.threads.split(",")]
    measured = {job: [] for job in jobs}
    outs = {}
    for round_index in range(args.rounds):
        for job in (jobs if round_index % 2 == 0 else reversed(jobs)):
            outs[job], values = run(args.talus, args.scenario.resolve(), *job, args.work)
            measured[job].append(values)
            print(f"round {round_index + 1}: {job[0]} {job[1]} {job[2]} thread(s): "
                  f"{values['wall_per_sim_s']:.3f} s per simulated second", file=sys.stderr)
    print("| path | setting | threads | wall per simulated second (s) | com1DFA's time over Talus's | "
          "particle-steps per simulated second (M) | us per particle-step | particle-steps per particle | "
          "area against com1DFA | IoU |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for job in jobs:
        path, setting, threads = job
        median = {key: statistics.median(v[key] for v in measured[job]) for key in measured[job][0]}
        reference = com1dfa_seconds(path)
        faster = f"{reference / median['wall_s']:.1f}x" if reference else "-"
        shown = figures(path, outs[job])
        print(f"| {path} | {setting} | {threads} | {median['wall_per_sim_s']:.3f} | {faster} | "
              f"{median['steps_per_sim_s']:.3f} | {median['us_per_step']:.2f} | {median['steps_per_particle']:.0f} | "
              f"{shown['area']} | {shown['iou']} |")


if __name__ == "__main__":
    main()
