#!/usr/bin/python3
"""Solves every reference graph with `dynslam solve` and prints one Markdown table next to
GTSAM 4.2's three profiles (SPEC §6): final cost, iterations, time, and the time ratios.

    scripts/reference_report.py [--reference DIR] [--dynslam BIN] [--out DIR] [-- solve options]

Timings are on this machine for dynslam; GTSAM's are those stored in the reference set (measured
on a 2-core machine of the same kind): ratios, not absolute times, are what to compare.
"""
import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent


def load(path):
    with open(path) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", default=str(ROOT / "build" / "release" / "data" / "reference"))
    parser.add_argument("--dynslam", default=str(ROOT / "build" / "release" / "apps" / "dynslam"))
    parser.add_argument("--out", default=str(ROOT / "out" / "reference"))
    parser.add_argument("solve_options", nargs="*", help="passed to dynslam solve (after --)")
    args = parser.parse_args()
    reference = pathlib.Path(args.reference)
    if not reference.is_dir():
        sys.exit(f"{reference}: no reference set here (give --reference DIR)")

    rows = []
    for graph in sorted(reference.glob("*/graphs/*.g2o")):
        scene, formulation = graph.parent.parent.name, graph.stem
        gtsam = reference / scene / "gtsam" / formulation
        out = pathlib.Path(args.out) / f"{scene}_{formulation}"
        print(f"solving {scene}/{formulation}", file=sys.stderr)
        run = subprocess.run([args.dynslam, "solve", str(graph), "--out", str(out)]
                             + args.solve_options, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"dynslam solve failed on {graph}:\n{run.stderr}")
        ours = load(out / "summary.json")
        profiles = {p: load(gtsam / p / "summary.json") for p in ("released", "tight", "tight_exact")}
        optimum = profiles["tight_exact"]["final_cost"]
        rows.append((scene, formulation, ours, profiles, optimum))

    print("| graph | dynslam final cost (rel. to tight_exact) | iter. | time s | GTSAM released: cost (rel.), iter., time s | tight: cost (rel.), iter., time s | tight_exact: iter., time s | time ratio released/ours | tight_exact/ours |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene, formulation, ours, p, optimum in rows:
        def rel(cost):
            return f"{(cost - optimum) / optimum:+.1e}"
        t = ours["time_s"]["total"]
        r, ti, te = p["released"], p["tight"], p["tight_exact"]
        print(f"| {scene}/{formulation} | {ours['final_cost']:.10g} ({rel(ours['final_cost'])}) | "
              f"{ours['iterations']} | {t:.2f} | "
              f"{r['final_cost']:.10g} ({rel(r['final_cost'])}), {r['iterations']}, {r['time_s']['total']:.2f} | "
              f"{ti['final_cost']:.10g} ({rel(ti['final_cost'])}), {ti['iterations']}, {ti['time_s']['total']:.2f} | "
              f"{te['iterations']}, {te['time_s']['total']:.2f} | "
              f"{r['time_s']['total'] / t:.2f} | {te['time_s']['total'] / t:.2f} |")


if __name__ == "__main__":
    main()
