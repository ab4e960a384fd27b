#!/usr/bin/python3
"""Debian's OpenBLAS builds against each other (issue 44: the threaded build that is safe for
concurrent solves must not be slower): every reference graph solved with the defaults by
`dynslam solve` under each build, alternating, ROUNDS times; prints a Markdown table of the
median total solve time (summary.json time_s.total) and checks that steps and final cost agree.
A build is chosen per run with LD_LIBRARY_PATH (Debian installs each in its own directory).

    benchmarks/blas_variants.py [--rounds 3] [--cli build/release/apps/dynslam]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
REFERENCE = os.path.join(ROOT, "build", "release", "data", "reference")  # unpacked by CMake
VARIANTS = {"serial": "/usr/lib/x86_64-linux-gnu/openblas-serial",
            "pthread": "/usr/lib/x86_64-linux-gnu/openblas-pthread"}


def graphs():
    for scene in sorted(os.listdir(REFERENCE)):
        folder = os.path.join(REFERENCE, scene, "graphs")
        if os.path.isdir(folder):
            for name in sorted(os.listdir(folder)):
                if name.endswith(".g2o"):
                    yield f"{scene}/{name[:-4]}", os.path.join(folder, name)


def solve(cli, graph, library_dir, out):
    env = dict(os.environ, LD_LIBRARY_PATH=library_dir)
    subprocess.run([cli, "solve", graph, "--out", out], env=env, check=True,
                   capture_output=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return summary["time_s"]["total"], summary["steps"], summary["final_cost"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--only", nargs="*", metavar="SCENE/GRAPH",
                        help="only these graphs, e.g. kitti_0003/oc_a")
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "release", "apps", "dynslam"))
    args = parser.parse_args()
    print("| graph | steps | serial s (median) | pthread s (median) | pthread / serial |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name, graph in graphs():
            if args.only and name not in args.only:
                continue
            times = {variant: [] for variant in VARIANTS}
            outcomes = set()
            for _ in range(args.rounds):
                for variant, library_dir in VARIANTS.items():
                    total, steps, cost = solve(args.cli, graph, library_dir, tmp)
                    times[variant].append(total)
                    outcomes.add((steps, cost))
            if len(outcomes) != 1:
                raise SystemExit(f"{name}: the builds disagree: {sorted(outcomes)}")
            serial, pthread = (statistics.median(times[v]) for v in VARIANTS)
            steps = next(iter(outcomes))[0]
            print(f"| {name} | {steps} | {serial:.3f} | {pthread:.3f} | {pthread / serial:.2f} |",
                  flush=True)


if __name__ == "__main__":
    main()
