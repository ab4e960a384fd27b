#!/usr/bin/env python3
"""Convergence study (issue 20, docs/CONVERGENCE.md): for each embedded KITTI sequence at full
length (seed 1), every formulation built with the default object start (`motion`) and from the
ground truth (`truth`), solved with each solver variant; steps and time to the optimum·(1 + 1e-6)
and to the solver's own stop, final cost, object motion error.

The optimum of a (sequence, formulation) is the lowest final cost any of its runs reached: every
start and variant minimises the same cost function (the starts differ only in later object poses
and points, the variants only in the solver's chart or residual frame).

  benchmarks/convergence_study.py --out DIR [--sequences 0000,0003] [--formulations wc,oc_b]
      [--variants default,…] [--frames A:B] [--dynslam PATH] [--timeout S]
  benchmarks/convergence_study.py --report DIR      the markdown tables of DIR/runs.csv (every
      run; then default start against `truth` start per sequence and formulation)

Variants (solver flags): default; object_points (`--object-point-variables object`);
object_kinematic (`--kinematic-residual-frame object`); before (both: the solver before issue 20).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEQUENCES = ["0000", "0001", "0002", "0003", "0004", "0005", "0006", "0018", "0020"]
FORMULATIONS = ["wc", "oc_a", "oc_b", "oc_c"]
VARIANTS = {
    "default": [],
    "object_points": ["--object-point-variables", "object"],
    "object_kinematic": ["--kinematic-residual-frame", "object"],
    "before": ["--object-point-variables", "object", "--kinematic-residual-frame", "object"],
}
FIELDS = ["sequence", "formulation", "init", "variant", "variables", "final_cost", "optimum",
          "steps_to_1e6", "time_to_1e6_s", "steps", "time_s", "termination",
          "motion_rot_deg", "motion_trans_m"]


def run(cmd, log, timeout=None):
    with open(log, "w") as out:
        return subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, timeout=timeout).returncode


def steps_to(rows, target):
    """First accepted step (and its time) whose cost is at or below target."""
    for r in rows:
        if r["accepted"] in ("1", "true") and float(r["trial_cost"]) <= target:
            return int(r["step"]), float(r["time_s"])
    return None, None


def solve_one(args, seq_dir, seq, formulation, init, variant):
    graph = os.path.join(seq_dir, f"{formulation}_{init}.g2o")
    if not os.path.exists(graph):
        run([args.dynslam, "build", os.path.join(seq_dir, "frontend.g2o"), "--formulation",
             formulation, "--gt", os.path.join(seq_dir, "frontend.gt.txt"), "--object-init", init,
             "--out", graph], graph + ".log")
    out = os.path.join(seq_dir, f"{formulation}_{init}_{variant}")
    if not os.path.exists(os.path.join(out, "summary.json")):
        start = time.time()
        try:
            run([args.dynslam, "solve", graph, "--gt", os.path.join(seq_dir, "frontend.gt.txt"),
                 "--out", out, "--tolerances", "tight"] + VARIANTS[variant], out + ".log",
                args.timeout)
        except subprocess.TimeoutExpired:
            print(f"  {seq} {formulation} {init} {variant}: timed out", file=sys.stderr)
            return None
        print(f"  {seq} {formulation} {init} {variant}: {time.time() - start:.1f} s",
              file=sys.stderr)
    summary_path = os.path.join(out, "summary.json")
    if not os.path.exists(summary_path):
        return None
    with open(summary_path) as f:
        summary = json.load(f)
    with open(os.path.join(out, "convergence.csv")) as f:
        rows = list(csv.DictReader(f))
    motion = summary.get("metrics", {}).get("object_motion", {})
    return {"sequence": seq, "formulation": formulation, "init": init, "variant": variant,
            "variables": summary["variables"]["total"], "final_cost": summary["final_cost"],
            "steps": summary["steps"], "time_s": summary["time_s"]["total"],
            "termination": summary["termination"],
            "motion_rot_deg": motion.get("mean_rot_deg"),
            "motion_trans_m": motion.get("mean_trans_m"), "_rows": rows}


def study(args):
    os.makedirs(args.out, exist_ok=True)
    commit = subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip()
    with open(os.path.join(args.out, "meta.json"), "w") as f:
        json.dump({"command": " ".join(sys.argv), "commit": commit,
                   "date": time.strftime("%Y-%m-%d")}, f, indent=1)
    results = []
    for seq in args.sequences:
        seq_dir = os.path.join(args.out, f"kitti_{seq}")
        os.makedirs(seq_dir, exist_ok=True)
        if not os.path.exists(os.path.join(seq_dir, "frontend.g2o")):
            frames = ["--frames", args.frames] if args.frames else []
            run([args.dynslam, "simulate", "--kitti", os.path.join(ROOT, "data", "kitti_tracking"),
                 "--seq", seq, "--seed", "1", "--out", os.path.join(seq_dir, "frontend")] + frames,
                os.path.join(seq_dir, "simulate.txt"))
        for formulation in args.formulations:
            inits = ["motion"] if formulation == "wc" else ["motion", "truth"]
            runs = [r for init in inits for variant in args.variants
                    if (r := solve_one(args, seq_dir, seq, formulation, init, variant))]
            if not runs:
                continue
            optimum = min(r["final_cost"] for r in runs)
            for r in runs:
                r["optimum"] = optimum
                r["steps_to_1e6"], r["time_to_1e6_s"] = steps_to(r.pop("_rows"),
                                                                 optimum * (1 + 1e-6))
                results.append(r)
            write_csv(os.path.join(args.out, "runs.csv"), results)


def write_csv(path, results):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        for r in results:
            writer.writerow({k: r.get(k) for k in FIELDS})


def fmt(value, spec):
    return "–" if value in (None, "", "None") else format(float(value), spec)


def report(directory):
    with open(os.path.join(directory, "runs.csv")) as f:
        runs = list(csv.DictReader(f))
    print("| seq | formulation | start | variant | variables | steps to 1e-6 | time to 1e-6 (s) "
          "| steps (stop) | time (s) | final / optimum − 1 | object motion (°, m) |")
    print("|---|---|---|---|---:|---:|---:|---:|---:|---:|---|")
    for r in runs:
        gap = float(r["final_cost"]) / float(r["optimum"]) - 1
        print(f"| {r['sequence']} | {r['formulation']} | {r['init']} | {r['variant']} "
              f"| {r['variables']} | {r['steps_to_1e6'] or '–'} | {fmt(r['time_to_1e6_s'], '.1f')} "
              f"| {r['steps']} | {fmt(r['time_s'], '.1f')} | {gap:.1e} "
              f"| {fmt(r['motion_rot_deg'], '.3f')}, {fmt(r['motion_trans_m'], '.3f')} |")


def check(directory):
    """Issue 20's criteria per (sequence, formulation): the default start's final cost against the
    `truth` start's, and its object motion error against that solve's."""
    with open(os.path.join(directory, "runs.csv")) as f:
        runs = [r for r in csv.DictReader(f) if r["variant"] == "default"]
    by_key = {(r["sequence"], r["formulation"], r["init"]): r for r in runs}
    print("| seq | formulation | default final / truth final − 1 | motion error default vs truth "
          "(rot, trans) | steps to 1e-6 (default start) |")
    print("|---|---|---:|---|---:|")
    for (seq, formulation, init), r in by_key.items():
        truth = by_key.get((seq, formulation, "truth"))
        if init != "motion" or truth is None:
            continue
        gap = float(r["final_cost"]) / float(truth["final_cost"]) - 1
        rot = float(r["motion_rot_deg"]) / float(truth["motion_rot_deg"]) - 1
        trans = float(r["motion_trans_m"]) / float(truth["motion_trans_m"]) - 1
        print(f"| {seq} | {formulation} | {gap:+.1e} | {rot:+.1%}, {trans:+.1%} "
              f"| {r['steps_to_1e6'] or '–'} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out")
    parser.add_argument("--report")
    parser.add_argument("--sequences", default=",".join(SEQUENCES))
    parser.add_argument("--formulations", default=",".join(FORMULATIONS))
    parser.add_argument("--variants", default="default")
    parser.add_argument("--frames")
    parser.add_argument("--timeout", type=float)
    parser.add_argument("--dynslam", default=os.path.join(ROOT, "build", "release", "apps",
                                                          "dynslam"))
    args = parser.parse_args()
    if args.report:
        report(args.report)
        print()
        check(args.report)
        return
    if not args.out:
        parser.error("--out DIR or --report DIR")
    args.sequences = args.sequences.split(",")
    args.formulations = args.formulations.split(",")
    args.variants = args.variants.split(",")
    unknown = [v for v in args.variants if v not in VARIANTS]
    if unknown:
        parser.error(f"unknown variants {unknown}; known: {sorted(VARIANTS)}")
    study(args)


if __name__ == "__main__":
    main()
