"""The work of a sweep, run on Dask workers: simulate a scene, then build, solve and score one
cell, each through the `dynslam` command (the same code and defaults as `dynslam compare`).

A task writes only under its own directory of the sweep's DIR and returns a plain dict; the
client alone writes the results database. Both tasks may run twice (Dask retries a task whose
worker died): they write whole files under temporary names and rename them.
"""
import json
import os
import socket
import subprocess
import time
import uuid

from ._sweep_tools import find_cli

# The SPEC §5 metric families of summary.json's "metrics" and the keys kept of each.
METRIC_FAMILIES = {
    "camera": ("mean_rot_deg", "mean_trans_m", "pairs"),
    "object_motion": ("mean_rot_deg", "mean_trans_m", "motions", "objects"),
    "object_pose": ("mean_rot_deg", "mean_trans_m", "pairs", "objects"),
}
METRIC_COLUMNS = [f"{family}_{key}" for family, keys in METRIC_FAMILIES.items() for key in keys]
# summary.json's "consistency" (solve --covariance with --gt): the mean NEES of each family.
NEES_COLUMNS = [f"{family}_nees" for family in METRIC_FAMILIES]
# Terminations of a finished solve (SPEC §4): the cell is done; "interrupted" is run again.
FINISHED = ("convergence", "no_convergence", "time_limit")


def _run(command, cwd=None):
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True)


def _problem(result, what):
    lines = (result.stderr or result.stdout).strip().splitlines()
    return f"{what} exited {result.returncode}: {lines[-1] if lines else 'no message'}"


def simulate(out_dir, scene, seed, frames, density, kitti, flags=()):
    """Writes OUT_DIR/frontend.{g2o,gt.txt} (and simulate.txt, the command's statistics) unless
    both are there; returns their paths, or raises RuntimeError with the command's message.
    `flags`: the simulation set's `dynslam simulate` options. The dynslam command is this
    worker's own (_sweep_tools.find_cli)."""
    cli = find_cli()
    os.makedirs(out_dir, exist_ok=True)
    prefix = os.path.join(out_dir, "frontend")
    if os.path.isfile(prefix + ".g2o") and os.path.isfile(prefix + ".gt.txt"):
        return prefix + ".g2o", prefix + ".gt.txt"
    temporary = os.path.join(out_dir, f".frontend-{uuid.uuid4().hex}")
    command = [cli, "simulate", "--seed", str(seed), "--out", temporary]
    command += ["--synthetic"] if scene == "synthetic" else ["--kitti", kitti, "--seq", scene]
    if frames:
        command += ["--frames", frames]
    if density == "paper":
        command += ["--density", "paper"]
    result = _run(command + list(flags))
    if result.returncode != 0:
        raise RuntimeError(_problem(result, "dynslam simulate"))
    with open(os.path.join(out_dir, "simulate.txt"), "w") as f:  # its statistics
        f.write(result.stdout)
    # The ground truth first: the .g2o's presence marks a complete pair.
    os.replace(temporary + ".gt.txt", prefix + ".gt.txt")
    os.replace(temporary + ".g2o", prefix + ".g2o")
    return prefix + ".g2o", prefix + ".gt.txt"


def _version(cli):
    result = _run([cli, "--version"])
    return result.stdout.strip() if result.returncode == 0 else ""


def run_cell(frontend, sweep_dir, cell, flags):
    """Builds and solves one cell in DIR/<cell.cell_dir>; returns its row of the results
    database (status 'ok', 'interrupted' or 'failed'). The dynslam command as for simulate."""
    cli = find_cli()
    graph_path, gt_path = frontend
    cell_dir = os.path.join(sweep_dir, cell.cell_dir)
    os.makedirs(cell_dir, exist_ok=True)
    row = cell.row(host=socket.gethostname(), version=_version(cli), status="failed", error="")
    started = time.monotonic()
    built = os.path.join(cell_dir, "graph.g2o")
    temporary = os.path.join(cell_dir, f".graph-{uuid.uuid4().hex}.g2o")
    result = _run([cli, "build", graph_path, "--formulation", cell.formulation, "--gt", gt_path,
                   "--out", temporary])
    if result.returncode != 0:
        row["error"] = _problem(result, "dynslam build")
        return row
    os.replace(temporary, built)
    # One thread per cell: a worker is one core (docs/SWEEPS.md); an option set may say otherwise.
    threads = [] if any(f.startswith("--threads=") for f in flags) else ["--threads=1"]
    summary_path = os.path.join(cell_dir, "summary.json")
    if os.path.exists(summary_path):
        os.remove(summary_path)  # so that one found below is this solve's
    result = _run([cli, "solve", built, "--gt", gt_path, "--out", cell_dir, *threads, *flags])
    row["wall_s"] = time.monotonic() - started
    if not os.path.isfile(summary_path):
        row["error"] = _problem(result, "dynslam solve")
        return row
    # A complete set of outputs: the solve's own status, whatever else failed (a singular
    # information matrix for --covariance exits 1 after writing them).
    with open(summary_path) as f:
        summary = json.load(f)
    row.update(summary_columns(summary))
    row["status"] = ("ok" if row["termination"] in FINISHED
                     else "interrupted" if row["termination"] == "interrupted" else "failed")
    if result.returncode not in (0, 130, 143):
        row["error"] = _problem(result, "dynslam solve")
    return row


def summary_columns(summary):
    """The results database's columns taken from a solve's summary.json (SPEC §4, §5)."""
    times = summary.get("time_s", {})
    columns = {
        "termination": summary["termination"],
        "steps": summary["steps"],
        "iterations": summary["iterations"],
        "initial_cost": summary["initial_cost"],
        "final_cost": summary["final_cost"],
        "solve_time_s": times.get("total"),
        "linear_solve_time_s": times.get("linear_solve"),
        # With --covariance: directions its information matrix leaves undetermined (0: none).
        "weak_directions": (len(summary["covariance"]["weak_directions"])
                            if "covariance" in summary else None),
    }
    metrics = summary.get("metrics") or {}
    consistency = summary.get("consistency") or {}
    for family, keys in METRIC_FAMILIES.items():
        for key in keys:
            columns[f"{family}_{key}"] = (metrics.get(family) or {}).get(key)
        nees = consistency.get(family) or {}
        columns[f"{family}_nees"] = nees.get("mean") if nees.get("count") else None
    return columns
