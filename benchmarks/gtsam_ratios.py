#!/usr/bin/env python3
"""Speed against GTSAM as one-run ratios (issue 22; the method of the reference set's TIMINGS.md).

TIMINGS.md times GTSAM 4.2 (`released` profile) and `dynslam solve` at commit ed665dc in one run on
one machine. Without GTSAM here, this script times ed665dc's binary (--base) and the current one
(--new) in one run of its own, alternating them, and carries each ratio over:

    ratio(new) = ratio(ed665dc, from TIMINGS.md) × time(ed665dc) / time(new)

for the whole process (reading the file to writing the outputs, each binary with its defaults)
and for the solve to GTSAM's `released` final cost (Ceres's preprocessing plus the minimiser time
at the first accepted step at or below that cost, as TIMINGS.md measures it).

    benchmarks/gtsam_ratios.py --base /tmp/dynslam_ed665dc --new build/release/apps/dynslam \
        --reference REFERENCE_SET [--reps 3] [--out docs/benchmarks/gtsam_ratios.csv]

Prints a Markdown table (medians of --reps runs) and writes every run to --out, the command,
date and commit to OUT.json; benchmarks/report.py puts the table into docs/BENCHMARKS.md.
"""
import argparse
import csv
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

GRAPHS = ["kitti_0003/oc_a", "kitti_0003/oc_b", "kitti_0003/oc_c", "kitti_0003/wc",
          "posegraph_parking-garage/pose_graph", "posegraph_sphere2500/pose_graph",
          "posegraph_torus3D/pose_graph", "synthetic/oc_a", "synthetic/oc_b", "synthetic/oc_c",
          "synthetic/wc"]


def timings_ratios(path):
    """graph -> (process ratio, solve ratio) from TIMINGS.md's table (last two columns)."""
    ratios = {}
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 6 and cells[0] in GRAPHS:
                ratios[cells[0]] = tuple(float(c.rstrip("×")) for c in cells[4:6])
    return ratios


def released_cost(reference, graph):
    scene, formulation = graph.split("/")
    with open(os.path.join(reference, scene, "gtsam", formulation, "released",
                           "summary.json")) as f:
        return json.load(f)["final_cost"]


def time_solve(binary, graph_path, out_dir, target_cost):
    """Process wall time, and preprocessing + minimiser time to the first accepted step at or
    below target_cost (None when never reached); the final cost and steps."""
    start = time.perf_counter()
    subprocess.run([binary, "solve", graph_path, "--out", out_dir], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    to_target = None
    with open(os.path.join(out_dir, "convergence.csv")) as f:
        for row in csv.DictReader(f):
            if row["accepted"] == "1" and float(row["trial_cost"]) <= target_cost:
                to_target = summary["time_s"]["preprocessing"] + float(row["time_s"])
                break
    return wall, to_target, summary["final_cost"], summary["steps"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", required=True, help="dynslam binary built at ed665dc")
    parser.add_argument("--new", required=True, help="dynslam binary to rate")
    parser.add_argument("--reference", required=True,
                        help="a reference set with the TIMINGS.md the ratios are carried from")
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--out", help="CSV of every run")
    args = parser.parse_args()

    ratios = timings_ratios(os.path.join(args.reference, "TIMINGS.md"))
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for graph in GRAPHS:
            scene, formulation = graph.split("/")
            path = os.path.join(args.reference, scene, "graphs", formulation + ".g2o")
            target = released_cost(args.reference, graph)
            for rep in range(args.reps):
                for name, binary in (("base", args.base), ("new", args.new)):
                    wall, to_target, final, steps = time_solve(
                        binary, path, os.path.join(tmp, name), target)
                    runs.append({"graph": graph, "binary": name, "rep": rep, "wall_s": wall,
                                 "to_gtsam_cost_s": to_target, "final_cost": final,
                                 "steps": steps})
    if args.out:
        with open(args.out, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(runs[0]))
            writer.writeheader()
            writer.writerows(runs)
        with open(args.out + ".json", "w") as f:
            json.dump({"command": "benchmarks/gtsam_ratios.py " + " ".join(sys.argv[1:]),
                       "date": datetime.date.today().isoformat(), "commit": commit(),
                       "machine": machine()}, f, indent=1)
    print("\n".join(table(runs, ratios)))


def machine():
    """The CPU model and core count (benchmarks/report.py names the page's machine with it)."""
    model = ""
    try:
        with open("/proc/cpuinfo") as f:
            model = next((line.split(":", 1)[1].strip() for line in f
                          if line.startswith("model name")), "")
    except OSError:
        pass
    return f"{model or platform.processor()}, {os.cpu_count()} cores"


def commit():
    """The checkout's commit (+ "-dirty" with uncommitted changes): what --new was built from."""
    here = os.path.dirname(os.path.abspath(__file__))
    head = subprocess.run(["git", "-C", here, "rev-parse", "--short", "HEAD"], text=True,
                          capture_output=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", here, "status", "--porcelain", "--untracked-files=no"],
                           text=True, capture_output=True).stdout.strip()
    return head + ("-dirty" if dirty else "")


def table(runs, ratios):
    """Markdown lines: per graph the medians of `runs` (dicts as in the CSV) and the carried
    ratios."""
    lines = ["| graph | dynslam: steps, process s | base: process s | GTSAM / dynslam, "
             "processes | dynslam: solve s to GTSAM's cost | base: same | GTSAM / dynslam, "
             "solve to GTSAM's cost |", "|---|---|---|---|---|---|---|"]
    for graph in GRAPHS:
        def median(binary, key):
            values = [float(r[key]) if r[key] not in (None, "") else None
                      for r in runs if r["graph"] == graph and r["binary"] == binary]
            return statistics.median(values) if values and None not in values else float("nan")
        process_ratio, solve_ratio = ratios[graph]
        new_wall, base_wall = median("new", "wall_s"), median("base", "wall_s")
        new_solve, base_solve = median("new", "to_gtsam_cost_s"), median("base", "to_gtsam_cost_s")
        lines.append(f"| {graph} | {median('new', 'steps'):.0f}, {new_wall:.2f} | {base_wall:.2f} | "
                     f"{process_ratio * base_wall / new_wall:.2f}× | {new_solve:.2f} | "
                     f"{base_solve:.2f} | {solve_ratio * base_solve / new_solve:.2f}× |")
    return lines


if __name__ == "__main__":
    main()
