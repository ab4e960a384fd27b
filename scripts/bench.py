#!/usr/bin/python3
"""`dynslam bench`: solvers compared on identical graph files (docs/GUIDE.md, "Comparing
solvers"). Each solver — a backend, a profile and options — solves each graph as its own
`dynslam solve` process; the table says how long it took, how much memory it held, where it
ended and how far that is from the best answer any of them found.

    dynslam bench GRAPH... --solvers ceres,ceres:tight,'ceres[linear_solver=sparse_schur]' \\
        --out DIR [--gt GT] [--repeat N]

A solver is BACKEND[:PROFILE][[OPTION=VALUE,...]]: `ceres` (the defaults), `ceres:tight` (a
`--tolerances` profile: default, tight, gtsam), `ceres[max_iterations=50,threads=2]` (any
`dynslam solve` options); `gtsam`, `gtsam:tight`, `gtsam:dogleg` (GTSAM's optimisers, a
`--backend gtsam:PROFILE` profile: released, tight, tight_exact, dogleg, gn; needs a dynslam
built with GTSAM, scripts/build_gtsam). Writes DIR/bench.csv (a row per graph and solver), DIR/bench.png (cost
above the best answer against time) and DIR/runs/<graph>/<solver>/ (each solve's outputs), and
prints the table. A solver that fails on a graph is a row whose status says why; the others run
on. Exit codes: 0 every solve finished, 1 some failed, 2 a bad command line (nothing run).
"""
import argparse
import csv
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time

import html_report  # beside this script: loads the package's _html module

BACKENDS = ("ceres", "gtsam")
PROFILES = ("default", "tight", "gtsam")
COLUMNS = ["graph", "solver", "status", "iterations", "wall_s", "peak_rss_mb", "final_cost",
           "chi2_above_best", "time_to_next_best_s", "max_rotation_diff_deg",
           "max_translation_diff_m"]
METRICS = [("camera", "mean_rot_deg"), ("camera", "mean_trans_m"),
           ("object_motion", "mean_rot_deg"), ("object_motion", "mean_trans_m"),
           ("object_pose", "mean_rot_deg"), ("object_pose", "mean_trans_m")]
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
HTML = html_report.load_html()  # its convergence.csv reader


class UsageError(Exception):
    pass


def parse_solver(text):
    """'ceres:tight[threads=2]' -> (backend, `dynslam solve` flags)."""
    match = re.fullmatch(r"([a-z]+)(?::([a-z_]+))?(?:\[([^\]]*)\])?", text)
    if not match:
        raise UsageError(f"'{text}' is not BACKEND[:PROFILE][[OPTION=VALUE,...]]")
    backend, profile, options = match.groups()
    if backend not in BACKENDS:
        raise UsageError(f"unknown backend '{backend}' in '{text}' (known: {', '.join(BACKENDS)})")
    flags = []
    if backend == "gtsam":  # GTSAM's profiles are checked by `dynslam solve --check-options`
        flags.append(f"--backend=gtsam:{profile}" if profile else "--backend=gtsam")
    elif profile:
        if profile not in PROFILES:
            raise UsageError(f"unknown profile '{profile}' in '{text}' (known: "
                             f"{', '.join(PROFILES)})")
        flags.append(f"--tolerances={profile}")
    for item in filter(None, (options or "").split(",")):
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise UsageError(f"'{item}' in '{text}' is not OPTION=VALUE")
        flags.append(f"--{key.strip().replace('_', '-')}={value.strip()}")
    return backend, flags


def graph_names(graphs):
    """Each graph's name in the table: its file's stem, or as many of its last folders as make
    the names unique (kitti_0003/graphs/oc_b.g2o and synthetic/graphs/oc_b.g2o: kitti_0003/oc_b
    and synthetic/oc_b, the folder `graphs` left out)."""
    def parts(graph):
        path = os.path.splitext(os.path.abspath(graph))[0].split(os.sep)
        return [p for p in path if p and p != "graphs"]
    for depth in range(1, 1 + max(len(parts(g)) for g in graphs)):
        names = {g: "/".join(parts(g)[-depth:]) for g in graphs}
        if len(set(names.values())) == len(graphs):
            return names
    return {g: f"{names[g]}_{i}" for i, g in enumerate(graphs)}  # the same file twice


def check_flags(dynslam, solver, flags):
    result = subprocess.run([dynslam, "solve", "-", "--check-options", *flags],
                            capture_output=True, text=True)
    if result.returncode != 0:
        lines = result.stderr.strip().splitlines()
        raise UsageError(f"'{solver}': {lines[0].removeprefix('error: ') if lines else 'bad options'}")


def slug(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_") or "solver"


def run_solve(dynslam, graph, flags, gt, out):
    """One `dynslam solve` process: (status, wall seconds, peak RSS in MB)."""
    command = [dynslam, "solve", graph, "--out", out, *flags] + (["--gt", gt] if gt else [])
    started = time.monotonic()
    with open(out + ".log", "w") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                   stdin=subprocess.DEVNULL)
        _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - started
    code = os.waitstatus_to_exitcode(status)
    if code == 0 and os.path.isfile(os.path.join(out, "summary.json")):
        return "ok", wall, usage.ru_maxrss / 1024
    with open(log.name) as f:
        lines = [line.strip() for line in f if line.strip()]
    reason = lines[-1].removeprefix("error: ") if lines else f"exit {code}"
    return f"failed: {reason}", wall, usage.ru_maxrss / 1024


def read_poses_and_points(path):
    """{id: (kind, values)} of a solution.g2o's vertices."""
    values = {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields[:1] == ["VERTEX_SE3:QUAT"]:
                values[fields[1]] = ("pose", [float(x) for x in fields[2:9]])
            elif fields[:1] == ["VERTEX_TRACKXYZ"]:
                values[fields[1]] = ("point", [float(x) for x in fields[2:5]])
    return values


def differences(a, b):
    """(largest rotation difference in degrees over poses, largest translation difference in
    metres over poses and points) between two solutions of one graph."""
    rotation, translation = 0.0, 0.0
    for key, (kind, x) in a.items():
        if key not in b:
            continue
        y = b[key][1]
        translation = max(translation, math.dist(x[:3], y[:3]))
        if kind == "pose":
            dot = abs(sum(p * q for p, q in zip(x[3:], y[3:])))
            rotation = max(rotation, math.degrees(2 * math.acos(min(1.0, dot))))
    return rotation, translation


def convergence(folder):
    """[(time_s, cost after the step)] of a solve's convergence.csv."""
    return [(time_s, cost) for _, time_s, cost in HTML.read_convergence(folder)]


def first_time_at(curve, cost, initial):
    """When a solve first reached `cost` (0 when it started there), or None."""
    if initial <= cost:
        return 0.0
    return next((t for t, c in curve if c <= cost), None)


def summarise(graph_name, runs, gt):
    """The rows of one graph: `runs` maps solver -> {folder, statuses, walls, rss}."""
    rows, finished = [], {}
    for solver, run in runs.items():
        status = next((s for s in run["statuses"] if s != "ok"), "ok")
        row = {"graph": graph_name, "solver": solver, "status": status,
               "wall_s": statistics.median(run["walls"]),
               "peak_rss_mb": statistics.median(run["rss"])}
        if row["status"] == "ok":
            with open(os.path.join(run["folder"], "summary.json")) as f:
                summary = json.load(f)
            row.update(iterations=summary["iterations"], final_cost=summary["final_cost"])
            if gt:
                metrics = summary.get("metrics") or {}
                for family, key in METRICS:
                    row[f"{family}_{key}"] = (metrics.get(family) or {}).get(key)
            finished[solver] = (summary, run["folder"])
        rows.append(row)
    if not finished:
        return rows
    best_solver = min(finished, key=lambda s: finished[s][0]["final_cost"])
    best_cost = finished[best_solver][0]["final_cost"]
    best_values = read_poses_and_points(os.path.join(finished[best_solver][1], "solution.g2o"))
    for row in rows:
        if row["solver"] not in finished:
            continue
        summary, folder = finished[row["solver"]]
        row["chi2_above_best"] = 2 * (summary["final_cost"] - best_cost)
        others = [finished[s][0]["final_cost"] for s in finished if s != row["solver"]]
        if others:
            row["time_to_next_best_s"] = first_time_at(convergence(folder), min(others),
                                                        summary["initial_cost"])
        rotation, translation = differences(
            read_poses_and_points(os.path.join(folder, "solution.g2o")), best_values)
        row["max_rotation_diff_deg"], row["max_translation_diff_m"] = rotation, translation
    return rows


def text(value):
    if value is None:
        return "–"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def print_table(rows, columns):
    print("| " + " | ".join(columns) + " |")
    print("|" + "---|" * len(columns))
    for row in rows:
        print("| " + " | ".join(text(row.get(c)) for c in columns) + " |")


def plot(out, graphs, runs_by_graph):
    """DIR/bench.png: cost above each graph's best answer against time, a line per solver."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("warning: no bench.png: /usr/bin/python3 has no matplotlib", file=sys.stderr)
        return
    figure, axes = plt.subplots(1, len(graphs), figsize=(6 * len(graphs), 4.2), squeeze=False)
    for panel, (name, rows) in zip(axes[0], graphs):
        costs = [r["final_cost"] for r in rows if r.get("final_cost") is not None]
        if not costs:
            continue
        best = min(costs)
        for solver, run in runs_by_graph[name].items():
            curve = convergence(run["folder"])
            if curve:
                panel.plot([t for t, _ in curve], [max(c - best, 1e-12) for _, c in curve],
                           marker=".", label=solver)
        panel.set_yscale("log")
        panel.set_xlabel("time (s)")
        panel.set_ylabel("cost above the best answer")
        panel.set_title(name, fontsize=10)
        panel.grid(alpha=0.3)
        panel.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(os.path.join(out, "bench.png"), dpi=100)
    plt.close(figure)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="dynslam bench", description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    parser.add_argument("graphs", nargs="+", metavar="GRAPH")
    parser.add_argument("--solvers", required=True, metavar="LIST",
                        help="comma-separated solvers (brackets may hold commas)")
    parser.add_argument("--out", required=True, metavar="DIR")
    parser.add_argument("--gt", help="ground truth (SPEC §2): the metrics of SPEC §5 too")
    parser.add_argument("--repeat", type=int, default=1, metavar="N",
                        help="run each solve N times, solvers alternating; medians of time and "
                             "memory")
    parser.add_argument("--dynslam", default=os.environ.get("DYNSLAM_CLI", "dynslam"),
                        help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    try:
        if args.repeat < 1:
            raise UsageError("--repeat must be at least 1")
        solvers = {}
        for name in re.findall(r"[^,\[]+(?:\[[^\]]*\])?", args.solvers):
            name = name.strip()
            if name in solvers:
                raise UsageError(f"'{name}' is listed twice")
            _, flags = parse_solver(name)
            check_flags(args.dynslam, name, flags)
            solvers[name] = flags
        if not solvers:
            raise UsageError("--solvers lists no solver")
        for graph in args.graphs:
            if not os.path.isfile(graph):
                raise UsageError(f"{graph}: no such file")
    except UsageError as error:
        print(f"error: {error}", file=sys.stderr)
        return EXIT_USAGE

    names = graph_names(args.graphs)
    runs_by_graph = {names[g]: {} for g in args.graphs}
    order = list(solvers)
    for repeat in range(args.repeat):
        for graph in args.graphs:
            for solver in order:
                folder = os.path.join(args.out, "runs", names[graph], slug(solver))
                run = runs_by_graph[names[graph]].setdefault(
                    solver, {"folder": folder, "statuses": [], "walls": [], "rss": []})
                os.makedirs(os.path.dirname(folder), exist_ok=True)
                status, wall, rss = run_solve(args.dynslam, graph, solvers[solver], args.gt, folder)
                run["statuses"].append(status)
                run["walls"].append(wall)
                run["rss"].append(rss)
                print(f"[bench] {names[graph]} {solver} run {repeat + 1}/{args.repeat}: {status}, "
                      f"{wall:.2f} s", file=sys.stderr)
        order = order[1:] + order[:1]  # alternate who goes first
    graphs = [(names[g], summarise(names[g], runs_by_graph[names[g]], args.gt))
              for g in args.graphs]
    rows = [row for _, rs in graphs for row in rs]
    columns = COLUMNS + ([f"{f}_{k}" for f, k in METRICS] if args.gt else [])
    with open(os.path.join(args.out, "bench.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    print_table(rows, COLUMNS[:9])
    plot(args.out, graphs, runs_by_graph)
    print(f"[bench] wrote {os.path.join(args.out, 'bench.csv')}", file=sys.stderr)
    return EXIT_OK if all(r["status"] == "ok" for r in rows) else EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
