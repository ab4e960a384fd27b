#!/usr/bin/python3
"""What marginal covariances cost against the solve (issue 45): simulates a KITTI sequence whole
at the front end's density (seed 1), builds the formulations, and solves each once with
`--covariance` (cameras and motions for wc, cameras and object poses for the object-centric
ones); prints a Markdown table of the solve's time (summary.json time_s.total), the
covariances' time and the information matrix's size, and the peak memory of the process
(GNU time: Debian's `time` package).

    benchmarks/covariance_cost.py [--seq 0020] [--formulations wc oc_b] [--out DIR]
"""
import argparse
import json
import os
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
KINDS = {"wc": "cameras,motions", "hy": "cameras,motions"}


def run(command):
    subprocess.run(command, check=True, capture_output=True, text=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seq", default="0020")
    parser.add_argument("--formulations", nargs="+", default=["wc", "oc_b"])
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "release", "apps", "dynslam"))
    parser.add_argument("--out", default=None)
    args = parser.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="covariance_cost_")
    os.makedirs(out, exist_ok=True)
    frontend = os.path.join(out, "frontend")
    run([args.cli, "simulate", "--seq", args.seq, "--seed", "1", "--out", frontend])
    print(f"| {args.seq} | variables | covariances of | columns | solve s | covariances s | peak RSS GB |")
    print("|---|---|---|---|---|---|---|")
    for formulation in args.formulations:
        graph = os.path.join(out, f"{formulation}.g2o")
        run([args.cli, "build", frontend + ".g2o", "--formulation", formulation,
             "--gt", frontend + ".gt.txt", "--out", graph])
        kinds = KINDS.get(formulation, "cameras,object_poses")
        solve_dir = os.path.join(out, formulation)
        result = subprocess.run(["/usr/bin/time", "-f", "%M", args.cli, "solve", graph,
                                 "--gt", frontend + ".gt.txt", "--out", solve_dir,
                                 "--covariance", kinds], capture_output=True, text=True)
        peak_kb = int(result.stderr.strip().splitlines()[-1])
        with open(os.path.join(solve_dir, "summary.json")) as f:
            summary = json.load(f)
        c = summary["covariance"]
        print(f"| {formulation} | {summary['variables']['total']} | {kinds} ({c['variables']}) | "
              f"{c['columns']} | {summary['time_s']['total']:.1f} | {c['time_s']:.1f} | "
              f"{peak_kb / 1e6:.2f} |", flush=True)


if __name__ == "__main__":
    main()
