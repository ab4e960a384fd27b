#!/usr/bin/python3
"""Convergence benchmarks (issue 13): solves graph files with `dynslam solve` under a grid of
solver configurations and writes one CSV row per run; times the factorisation floor of each graph
(benchmarks/factorization_floor) and, with --scaling, solves simulated scenes of growing length
(KITTI 0020 and the synthetic scene). benchmarks/report.py turns the CSVs into docs/BENCHMARKS.md.

    benchmarks/sweep.py                         # the reference graphs, every configuration
    benchmarks/sweep.py --quick                 # linear solvers at the defaults only
    benchmarks/sweep.py --graphs a.g2o b.g2o --configs default snc_eigen
    benchmarks/sweep.py --scaling               # also the scaling runs (KITTI 0020 and synthetic,
                                                # at most 25 steps each: time per step and peak
                                                # memory)
    benchmarks/sweep.py --scaling-only          # the scaling runs alone (scaling.csv)

Outputs (default out/benchmarks/): runs.csv, floor.csv, scaling.csv. Every run is on one graph
file, the same file for every configuration. Time to a target cost is read from the run's
convergence.csv (SPEC §4): the time of the first accepted step whose cost is at or below the
target. Targets come from the reference set when the graph is one of its graphs: GTSAM's
`released` final cost and `tight_exact`·(1 + 1e-6).
"""
import argparse
import csv
import datetime
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import threading
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Linear solver × backend (issue 13's list).
LINEAR = {
    "schur_suitesparse": ["--linear-solver", "sparse_schur", "--sparse-backend", "suitesparse"],
    "schur_eigen": ["--linear-solver", "sparse_schur", "--sparse-backend", "eigen"],
    "snc_suitesparse": ["--linear-solver", "sparse_normal_cholesky", "--sparse-backend", "suitesparse"],
    "snc_eigen": ["--linear-solver", "sparse_normal_cholesky", "--sparse-backend", "eigen"],
    "iterative_schur": ["--linear-solver", "iterative_schur"],
}
# LM settings: dynslam's defaults (the remaining-χ² rule 0.01, tolerances 1e-12, 500
# iterations); its tight rule (the tolerances alone); GTSAM-like (the released profile: first
# damping 1e-5, stop at a relative decrease of 1e-5, 100 iterations); Ceres's own defaults
# (tolerances 1e-6 / 1e-10 / 1e-8, 50 iterations, first damping 1e-4).
LM = {
    "dynslam": [],
    "tight": ["--tolerances", "tight"],
    "gtsam_like": ["--initial-lambda", "1e-5", "--function-tolerance", "1e-5",
                   "--max-iterations", "100"],
    "ceres_defaults": ["--function-tolerance", "1e-6", "--gradient-tolerance", "1e-10",
                       "--parameter-tolerance", "1e-8", "--max-iterations", "50"],
}
THREADS = [1, 2]

FIELDS = ["graph", "formulation", "config", "linear", "lm", "threads", "minimizer", "variables",
          "edges", "initial_cost", "final_cost", "rel_to_optimum", "iterations", "steps",
          "termination", "time_total", "time_preprocessing", "time_evaluation",
          "time_linear_solve", "time_per_step", "time_to_released", "steps_to_released",
          "time_to_optimum_1e6", "steps_to_optimum_1e6", "gtsam_released_total",
          "gtsam_released_iterations", "peak_rss_mb"]


def configurations(names, quick):
    """(name, linear, lm, threads, minimizer, flags) for every configuration asked for."""
    grid = []
    for linear, linear_flags in LINEAR.items():
        for lm, lm_flags in LM.items():
            for threads in THREADS:
                if quick and (lm != "dynslam" or threads != 1):
                    continue
                name = f"{linear}/{lm}/t{threads}"
                grid.append((name, linear, lm, threads, "lm",
                             ["--minimizer", "lm"] + linear_flags + lm_flags +
                             ["--threads", str(threads)]))
    grid.append(("dogleg/dynslam/t1", "schur_suitesparse", "dynslam", 1, "dogleg",
                 LINEAR["schur_suitesparse"] + ["--minimizer", "dogleg"]))
    grid.append(("dogleg_snc_eigen/dynslam/t1", "snc_eigen", "dynslam", 1, "dogleg",
                 LINEAR["snc_eigen"] + ["--minimizer", "dogleg"]))
    grid.append(("dogleg_snc_suitesparse/dynslam/t1", "snc_suitesparse", "dynslam", 1, "dogleg",
                 LINEAR["snc_suitesparse"] + ["--minimizer", "dogleg"]))
    grid.append(("default/t2", "default", "default", 2, "default", ["--threads", "2"]))
    grid.append(("monotonic/dynslam/t1", "snc_suitesparse", "dynslam", 1, "lm",
                 ["--minimizer", "lm"] + LINEAR["snc_suitesparse"] +
                 ["--nonmonotonic-steps", "0"]))
    grid.append(("default", "default", "default", 1, "default", []))
    if names:
        grid = [c for c in grid if c[0] in names or c[1] in names]
    return grid


def run_measured(command, timeout=None):
    """Runs `command`; returns (exit code, stdout, stderr, peak RSS in MB of that process).
    After `timeout` seconds the process is killed (exit code −9)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        process = subprocess.Popen(command, stdout=out, stderr=err)
        timer = threading.Timer(timeout, process.kill) if timeout else None
        if timer:
            timer.start()
        _, status, usage = os.wait4(process.pid, 0)
        if timer:
            timer.cancel()
        process.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        return (process.returncode, out.read().decode(), err.read().decode(),
                usage.ru_maxrss / 1024.0)


def first_reaching(convergence_csv, target):
    """(time_s, step) of the first accepted step at or below `target`, or ("", "")."""
    if target is None:
        return "", ""
    with open(convergence_csv, newline="") as f:
        for row in csv.DictReader(f):
            if row["accepted"] in ("1", "true") and float(row["trial_cost"]) <= target:
                return float(row["time_s"]), int(row["step"])
    return "", ""


def reference_targets(graph):
    """GTSAM's released summary and the tight_exact optimum for a graph of the reference set."""
    gtsam = graph.parent.parent / "gtsam" / graph.stem
    try:
        with open(gtsam / "released" / "summary.json") as f:
            released = json.load(f)
        with open(gtsam / "tight_exact" / "summary.json") as f:
            optimum = json.load(f)["final_cost"]
    except (OSError, KeyError, ValueError):
        return None, None
    return released, optimum


def solve_row(dynslam, graph, config, work, timeout=None):
    name, linear, lm, threads, minimizer, flags = config
    out = work / "solve"
    code, _, err, peak = run_measured([dynslam, "solve", str(graph), "--out", str(out)] + flags,
                                      timeout)
    if code == -9 and timeout:
        return {"graph": str(graph), "config": name, "linear": linear, "lm": lm,
                "threads": threads, "minimizer": minimizer, "termination": "timeout",
                "time_total": float(timeout), "peak_rss_mb": f"{peak:.1f}"}
    if code != 0:
        sys.exit(f"dynslam solve {graph} {' '.join(flags)} failed (exit {code}):\n{err}")
    with open(out / "summary.json") as f:
        s = json.load(f)
    released, optimum = reference_targets(graph)
    released_cost = released["final_cost"] if released else None
    t_released, n_released = first_reaching(out / "convergence.csv", released_cost)
    t_optimum, n_optimum = first_reaching(out / "convergence.csv",
                                          optimum * (1 + 1e-6) if optimum else None)
    t = s["time_s"]
    return {
        "graph": str(graph), "formulation": s["formulation"], "config": name, "linear": linear,
        "lm": lm, "threads": threads, "minimizer": minimizer,
        "variables": s["variables"]["total"], "edges": s["edges"]["total"],
        "initial_cost": repr(s["initial_cost"]), "final_cost": repr(s["final_cost"]),
        "rel_to_optimum": f"{(s['final_cost'] - optimum) / optimum:.3e}" if optimum else "",
        "iterations": s["iterations"], "steps": s["steps"], "termination": s["termination"],
        "time_total": t["total"], "time_preprocessing": t["preprocessing"],
        "time_evaluation": t["residual_jacobian_evaluation"],
        "time_linear_solve": t["linear_solve"],
        "time_per_step": t["minimizer"] / max(1, s["steps"]),
        "time_to_released": t_released, "steps_to_released": n_released,
        "time_to_optimum_1e6": t_optimum, "steps_to_optimum_1e6": n_optimum,
        "gtsam_released_total": released["time_s"]["total"] if released else "",
        "gtsam_released_iterations": released["iterations"] if released else "",
        "peak_rss_mb": f"{peak:.1f}",
    }


def floor_rows(floor_binary, graph, repeat):
    code, out, err, _ = run_measured([floor_binary, str(graph), "--repeat", str(repeat)])
    if code != 0:
        sys.exit(f"factorization_floor {graph} failed:\n{err}")
    return list(csv.DictReader(out.splitlines()))


def scaling_rows(dynslam, scenes, formulations, max_steps, work):
    """Simulates each scene (sequence, frames, `dynslam simulate` flags), builds each formulation
    and solves it with the defaults for at most `max_steps` linear solves."""
    rows = []
    for sequence, frames, simulate_flags in scenes:
        prefix = work / f"seq{sequence}_{frames}"
        subprocess.run([dynslam, "simulate"] + simulate_flags + ["--seed", "1", "--out", str(prefix)],
                       check=True, capture_output=True)
        for formulation in formulations:
            built = work / f"seq{sequence}_{frames}_{formulation}.g2o"
            subprocess.run([dynslam, "build", f"{prefix}.g2o", "--formulation", formulation,
                            "--gt", f"{prefix}.gt.txt", "--out", str(built)],
                           check=True, capture_output=True)
            # The defaults, at most max_steps linear solves: time per step is the measure.
            row = solve_row(dynslam, built, ("default", "default", "default", 1, "default",
                                             ["--max-iterations", str(max_steps)]), work)
            row.update({"frames": frames, "sequence": sequence})
            rows.append(row)
            print(f"  scaling {sequence} frames 0:{frames} {formulation}: "
                  f"{row['variables']} variables, {row['steps']} steps, "
                  f"{row['time_total']:.2f} s, {row['peak_rss_mb']} MB", file=sys.stderr)
            built.unlink()
        for suffix in (".g2o", ".gt.txt"):
            pathlib.Path(f"{prefix}{suffix}").unlink()
    return rows


def source_version():
    """The commit the sweep runs on (`git describe --always --dirty`), or "unknown"."""
    result = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
                            capture_output=True, text=True)
    return result.stdout.strip() or "unknown"


def write_csv(path, rows, fields):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", default=str(ROOT / "build" / "release" / "data" / "reference"))
    parser.add_argument("--graphs", nargs="*", help="graph files (default: every reference graph)")
    parser.add_argument("--configs", nargs="*", help="configuration or linear-solver names")
    parser.add_argument("--quick", action="store_true",
                        help="only dynslam's LM settings, one thread")
    parser.add_argument("--scaling", action="store_true", help="also the scaling runs")
    parser.add_argument("--scaling-only", action="store_true",
                        help="only the scaling runs (runs.csv and floor.csv are left as they are)")
    parser.add_argument("--scaling-lengths", nargs="*", type=int,
                        default=[50, 100, 200, 400, 837], help="KITTI 0020 frames")
    parser.add_argument("--scaling-synthetic-frames", nargs="*", type=int,
                        default=[300, 1200, 4800, 12800, 25600],
                        help="frames of the synthetic scene (25600: 763k wc variables, 6.5 GB)")
    parser.add_argument("--scaling-formulations", nargs="*", default=["wc", "oc_b"])
    parser.add_argument("--scaling-max-steps", type=int, default=25,
                        help="linear solves per scaling run (time per step is the measure; wc "
                             "converges before)")
    parser.add_argument("--kitti", default=str(ROOT / "data" / "kitti_tracking"))
    parser.add_argument("--build", default=str(ROOT / "build" / "release"))
    parser.add_argument("--repeat", type=int, default=5, help="factorisations per floor timing")
    parser.add_argument("--out", default=str(ROOT / "out" / "benchmarks"))
    parser.add_argument("--append", action="store_true",
                        help="add rows to OUT/runs.csv and scaling.csv instead of replacing them")
    parser.add_argument("--no-floor", action="store_true", help="skip the factorisation floor")
    parser.add_argument("--timeout", type=float, default=300,
                        help="seconds before a solve is stopped (row: termination timeout)")
    args = parser.parse_args()

    build = pathlib.Path(args.build)
    dynslam = build / "apps" / "dynslam"
    floor_binary = build / "benchmarks" / "factorization_floor"
    for binary in (dynslam, floor_binary):
        if not binary.exists():
            sys.exit(f"{binary}: not built (cmake --build {build} --target dynslam_cli "
                     "factorization_floor)")
    graphs = [pathlib.Path(g) for g in args.graphs] if args.graphs else sorted(
        pathlib.Path(args.reference).glob("*/graphs/*.g2o"))
    if args.scaling_only:
        graphs, args.scaling = [], True
    elif not graphs:
        sys.exit(f"no graphs (give --graphs, or --reference DIR with */graphs/*.g2o)")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    runs, floors = [], []
    if args.append and (out / "runs.csv").exists():
        with open(out / "runs.csv", newline="") as f:
            runs = list(csv.DictReader(f))
    started = time.monotonic()
    version, date = source_version(), datetime.date.today().isoformat()
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        for graph in graphs:
            if not args.no_floor:
                floors += floor_rows(floor_binary, graph, args.repeat)
            for config in configurations(args.configs, args.quick):
                row = solve_row(dynslam, graph, config, work, args.timeout)
                runs.append(row)
                print(f"{graph.parent.parent.name}/{graph.stem} {config[0]}: "
                      f"{row.get('steps', '—')} steps, {row['time_total']:.2f} s, "
                      f"{row['termination']}, rel {row.get('rel_to_optimum', '—')}",
                      file=sys.stderr)
                write_csv(out / "runs.csv", runs, FIELDS)
            if floors:
                write_csv(out / "floor.csv", floors, list(floors[0].keys()))
        if args.scaling:
            scenes = [("0020", n, ["--kitti", args.kitti, "--seq", "0020", "--frames", f"0:{n}"])
                      for n in args.scaling_lengths]
            scenes += [("synthetic", n, ["--synthetic", "--synthetic-frames", str(n)])
                       for n in args.scaling_synthetic_frames]
            rows = []
            if args.append and (out / "scaling.csv").exists():
                with open(out / "scaling.csv", newline="") as f:
                    rows = list(csv.DictReader(f))
            rows += scaling_rows(dynslam, scenes, args.scaling_formulations,
                                 args.scaling_max_steps, work)
            write_csv(out / "scaling.csv", rows, ["sequence", "frames"] + FIELDS)
    # Every sweep that wrote into OUT, in order (report.py quotes them as the reproduction).
    sweeps = []
    if (args.append or args.scaling_only) and (out / "meta.json").exists():
        sweeps = json.loads((out / "meta.json").read_text()).get("sweeps", [])
    sweeps.append({"command": " ".join(["benchmarks/sweep.py"] + sys.argv[1:]),
                   "seconds": round(time.monotonic() - started), "commit": version,
                   "date": date})
    (out / "meta.json").write_text(json.dumps({"sweeps": sweeps}, indent=1) + "\n")
    written = ([] if args.scaling_only else ["runs.csv", "floor.csv"]) + ["meta.json"] + (
        ["scaling.csv"] if args.scaling else [])
    print(f"wrote {out}/: {', '.join(written)}", file=sys.stderr)


if __name__ == "__main__":
    main()
