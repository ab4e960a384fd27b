"""`python3 -m dynslam.sweep` (issue 41): bad sweep files, the statistics against SciPy, and real
Dask clusters — a scheduler and two workers on 127.0.0.1, one of them killed mid-sweep — and an
interrupted local sweep. Needs PYTHONPATH=<build>/python and DYNSLAM_CLI (as ctest sets them)."""
import json
import math
import os
import signal
import socket
import sqlite3
import subprocess
import sys
import time

import numpy as np
import pytest
from scipy import stats

from dynslam import _sweep_stats as st

CLI = os.environ.get("DYNSLAM_CLI")
SMALL_SWEEP = """
scenes = ["synthetic", "0003"]
frames = "0:30"
seeds = [1, 2, 3]
formulations = ["wc", "oc_b"]
[options.default]
"""


def sweep_command(*args):
    return [sys.executable, "-m", "dynslam.sweep", *args]


def run_sweep(*args, **kwargs):
    return subprocess.run(sweep_command(*args), capture_output=True, text=True, **kwargs)


def write(path, text):
    path.write_text(text)
    return str(path)


def cell_rows(out):
    with sqlite3.connect(os.path.join(out, "results.sqlite")) as connection:
        connection.row_factory = sqlite3.Row
        return [dict(r) for r in connection.execute("SELECT * FROM cells")]


# --- bad sweep files: one error naming the file and the key, exit 2, nothing run ---

@pytest.mark.parametrize("text, key", [
    ("colour = 'red'\n" + SMALL_SWEEP, "colour"),
    (SMALL_SWEEP.replace('"oc_b"', '"oc_z"'), "formulations"),
    (SMALL_SWEEP.replace('"0003"', '"0099"'), "scenes"),
    (SMALL_SWEEP + "[options.bad]\nmax_iterations = 'many'\n", "options.bad.max_iterations"),
    (SMALL_SWEEP + "[options.bad]\nminimizer = 'newton'\n", "options.bad.minimizer"),
    (SMALL_SWEEP + "[options.bad]\nno_such_option = 1\n", "options.bad.no_such_option"),
    (SMALL_SWEEP.replace("seeds = [1, 2, 3]", "seeds = []"), "seeds"),
    (SMALL_SWEEP.replace("seeds = [1, 2, 3]", 'seeds = "5:2"'), "seeds"),
    (SMALL_SWEEP.replace('frames = "0:30"', 'frames = "thirty"'), "frames"),
    (SMALL_SWEEP.replace('frames = "0:30"', 'density = "paper"'), "density"),
    (SMALL_SWEEP + "[options.bad]\nout = 'elsewhere'\n", "options.bad.out"),
    (SMALL_SWEEP + "[simulate.bad]\npixel_sigma = -1.0\n", "simulate.bad.pixel_sigma"),
    (SMALL_SWEEP + "[simulate.bad]\npixel_sigma = 'small'\n", "simulate.bad.pixel_sigma"),
    (SMALL_SWEEP + "[simulate.bad]\nno_such_setting = 1\n", "simulate.bad.no_such_setting"),
    (SMALL_SWEEP + "[simulate.bad]\nseed = 3\n", "simulate.bad.seed"),
    (SMALL_SWEEP + "[simulate.bad]\noutlier_min = 2.0\noutlier_max = 1.0\n", "simulate.bad"),
    ("simulate = 3\n" + SMALL_SWEEP, "simulate"),
    (SMALL_SWEEP + "[options.bad]\nbackend = 'gtsam:fast'\n", "options.bad.backend"),
])
def test_bad_sweep_file_is_one_error_and_runs_nothing(tmp_path, text, key):
    path = write(tmp_path / "bad.toml", text)
    out = tmp_path / "out"
    result = run_sweep(path, "--out", str(out))
    assert result.returncode == 2, result.stderr
    assert result.stderr.startswith(f"error: {path}: {key}: "), result.stderr
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert not out.exists()


def test_a_backend_this_build_lacks_is_named_before_anything_runs(tmp_path):
    if CLI is None:
        pytest.skip("DYNSLAM_CLI is not set")
    check = subprocess.run([CLI, "solve", "-", "--check-options", "--backend=gtsam"],
                           capture_output=True, text=True)
    if check.returncode == 0:
        pytest.skip("this dynslam has the GTSAM backend")
    path = write(tmp_path / "gtsam.toml", SMALL_SWEEP + "[options.gtsam]\nbackend = 'gtsam'\n")
    result = run_sweep(path, "--out", str(tmp_path / "out"))
    assert result.returncode == 2
    assert result.stderr.startswith(f"error: {path}: options.gtsam.backend: "), result.stderr
    assert "scripts/build_gtsam" in result.stderr
    assert not (tmp_path / "out").exists()


def test_missing_and_unreadable_sweep_files(tmp_path):
    result = run_sweep(str(tmp_path / "absent.toml"), "--out", str(tmp_path / "out"))
    assert result.returncode == 2 and "absent.toml" in result.stderr
    path = write(tmp_path / "broken.toml", "scenes = [\n")
    result = run_sweep(path, "--out", str(tmp_path / "out"))
    assert result.returncode == 2 and "not TOML" in result.stderr


# --- statistics against SciPy on fixed numbers ---

def test_mean_deviation_and_interval_match_scipy():
    x = [0.12, 0.15, 0.11, 0.19, 0.14, 0.13]
    d = st.describe(x)
    low, high = stats.t.interval(0.95, len(x) - 1, loc=np.mean(x), scale=stats.sem(x))
    assert d["n"] == 6
    assert d["mean"] == pytest.approx(np.mean(x), rel=1e-15)
    assert d["sd"] == pytest.approx(np.std(x, ddof=1), rel=1e-15)
    assert (d["ci_low"], d["ci_high"]) == (pytest.approx(low, rel=1e-12), pytest.approx(high, rel=1e-12))
    assert math.isnan(st.describe([1.0])["ci_low"]) and st.describe([])["n"] == 0


def test_wilcoxon_matches_scipy_and_holm_matches_its_definition():
    a = [1.3, 2.1, 0.4, 5.5, 3.2, 2.2, 0.9, 1.8]
    b = [1.1, 2.5, 0.1, 4.9, 2.0, 2.0, 0.3, 1.0]
    differences = np.subtract(a, b)
    assert st.wilcoxon(differences) == pytest.approx(stats.wilcoxon(a, b).pvalue, rel=1e-12)
    # Holm: sort p ascending, multiply the i-th (from 0) by m − i, keep the running maximum.
    assert st.holm([0.01, 0.04, 0.03]) == pytest.approx([0.03, 0.06, 0.06])
    assert st.holm([0.5, math.nan, 0.01]) == pytest.approx([0.5, math.nan, 0.02], nan_ok=True)
    assert st.holm([0.9, 0.8]) == pytest.approx([1.0, 1.0])  # 2 × 0.8 capped at 1


def test_the_median_interval_covers_with_at_least_95_percent_and_is_the_narrowest_so():
    values = list(range(100, 120))  # n = 20: ranks 6 and 15 (1-based), coverage 95.86 %
    assert st.median_interval(values) == (105.0, 114.0)
    for n in (6, 7, 10, 11, 30, 90):
        low, high = st.median_interval(list(range(n)))
        j = int(low)  # values are their ranks − 1, so j is the lower rank − 1
        assert high == n - 1 - j
        assert 1 - 2 * stats.binom.cdf(j, n, 0.5) >= 0.95
        assert 1 - 2 * stats.binom.cdf(j + 1, n, 0.5) < 0.95  # one rank further in: too narrow
    assert all(math.isnan(x) for x in st.median_interval([1, 2, 3, 4, 5]))


def test_axes_are_the_options_a_set_changes_from_the_defaults():
    from dynslam._sweep_sensitivity import axes
    defaults = {"pixel_sigma": "0.5", "disparity_sigma": "0.5", "noise_every_edge": "off",
                "odometry_rotation_sigma": "0.002"}
    sets = {"default": {}, "pixel_1": {"pixel_sigma": 1.0, "disparity_sigma": 1.0},
            "pixel_2": {"pixel_sigma": 2.0, "disparity_sigma": 2.0},
            "every_edge": {"noise_every_edge": True}, "odometry_x2": {"odometry_rotation_sigma": 0.004},
            "same": {"pixel_sigma": 0.5}}  # the default value: no axis of its own
    assert axes(sets, defaults) == {
        "disparity_sigma + pixel_sigma": [(0.5, "default"), (1.0, "pixel_1"), (2.0, "pixel_2")],
        "noise_every_edge": [(0.0, "default"), (1.0, "every_edge")],
        "odometry_rotation_sigma": [(0.002, "default"), (0.004, "odometry_x2")]}


def test_a_formulation_against_itself_is_never_significant():
    rows = []
    for seed in range(10):
        for formulation in ("wc", "wc_again"):
            row = {"status": "ok", "scene": "s", "seed": seed, "options": "default",
                   "formulation": formulation}
            row.update({metric: 0.1 * seed + 1 for metric, _ in st.METRICS})
            rows.append(row)
    comparisons = st.paired(rows)
    assert comparisons and all(c["p"] == 1.0 and not c["significant"] for c in comparisons)
    assert all(c["median_difference"] == 0 and c["pairs"] == 10 for c in comparisons)


# --- scheduling: the cells of larger front ends first ---

def test_cells_wait_largest_front_end_first_ties_in_order(tmp_path):
    from dynslam.sweep import LargestFirst
    from dynslam._sweep_spec import Cell
    waiting = LargestFirst()
    for scene, size in (("small", 10), ("large", 1000), ("middle", 100)):
        frontend = (write(tmp_path / f"{scene}.g2o", "x" * size), str(tmp_path / "gt.txt"))
        waiting.add(frontend, [Cell(scene, 1, f, "default") for f in ("wc", "oc_a")])
    order = []
    while waiting:
        frontend, cell = waiting.pop()
        order.append((cell.scene, cell.formulation))
        if len(order) == 1:  # a late arrival larger than what waits goes first
            waiting.add((write(tmp_path / "late.g2o", "x" * 500), ""), [Cell("late", 1, "wc", "x")])
    assert order == [("large", "wc"), ("large", "oc_a"), ("late", "wc"), ("middle", "wc"),
                     ("middle", "oc_a"), ("small", "wc"), ("small", "oc_a")]


# --- real Dask clusters ---

def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def cluster():
    """A `dask scheduler` and two `dask worker` processes (no nanny, so that killing one kills
    it) on 127.0.0.1; yields (address, workers) and stops them all."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    dask = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    scheduler = subprocess.Popen(dask + ["--host", "127.0.0.1", "--port", str(port),
                                         "--no-dashboard"],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                                 "--nthreads", "1", "--no-nanny", "--no-dashboard",
                                 "--host", "127.0.0.1"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
               for _ in range(2)]
    from dask.distributed import Client
    with Client(address, timeout=60) as client:
        client.wait_for_workers(2, timeout=60)
    yield address, workers
    for process in workers + [scheduler]:
        process.kill()
        process.wait()


def direct_solve(out, row, tmp_path):
    """`dynslam solve` of a cell's graph.g2o, as a user would run it: its summary.json."""
    cell = os.path.join(out, row["cell_dir"])
    frontend = os.path.join(os.path.dirname(cell), "frontend.gt.txt")
    direct = tmp_path / "direct" / row["cell_dir"]
    subprocess.run([CLI, "solve", os.path.join(cell, "graph.g2o"), "--gt", frontend,
                    "--out", str(direct)], check=True, capture_output=True)
    with open(direct / "summary.json") as f:
        return json.load(f)


def test_sweep_on_a_dask_cluster_equals_direct_solves(tmp_path, cluster):
    address, _ = cluster
    out = str(tmp_path / "out")
    result = run_sweep(write(tmp_path / "s.toml", SMALL_SWEEP), "--out", out,
                       "--scheduler", address, timeout=600)
    assert result.returncode == 0, result.stderr
    rows = cell_rows(out)
    assert len(rows) == 12 and all(r["status"] == "ok" for r in rows)
    for row in rows:
        summary = direct_solve(out, row, tmp_path)
        assert row["final_cost"] == pytest.approx(summary["final_cost"], rel=1e-12)
        assert row["steps"] == summary["steps"]
        for family in ("camera", "object_motion", "object_pose"):
            for key in ("mean_rot_deg", "mean_trans_m"):
                assert row[f"{family}_{key}"] == pytest.approx(
                    summary["metrics"][family][key], rel=1e-12)
    assert os.path.isfile(os.path.join(out, "results.csv"))
    os.remove(os.path.join(out, "report.md"))
    report = run_sweep("report", out, timeout=120)
    assert report.returncode == 0, report.stderr
    with open(os.path.join(out, "report.md")) as f:
        text = f.read()
    assert "| synthetic | oc_b | 3 |" in text and "| default | oc_b | camera_mean_rot_deg | 6 |" in text


def test_a_killed_worker_costs_only_a_rerun_of_its_cell(tmp_path, cluster):
    address, workers = cluster
    out = str(tmp_path / "out")
    sweep = subprocess.Popen(sweep_command(write(tmp_path / "s.toml", SMALL_SWEEP), "--out", out,
                                           "--scheduler", address),
                             stderr=subprocess.PIPE, text=True)
    for line in sweep.stderr:  # the first finished cell: the others are queued or running
        if line.startswith("cell "):
            workers[0].send_signal(signal.SIGKILL)
            break
    sweep.stderr.read()
    assert sweep.wait(timeout=600) == 0
    rows = cell_rows(out)
    keys = {(r["scene"], r["seed"], r["formulation"], r["options"]) for r in rows}
    assert len(rows) == len(keys) == 12 and all(r["status"] == "ok" for r in rows)
    again = run_sweep(str(tmp_path / "s.toml"), "--out", out, "--scheduler", address, timeout=120)
    assert again.returncode == 0, again.stderr
    assert "12 finished before, 0 to run" in again.stderr


def test_an_interrupted_local_sweep_keeps_its_finished_cells(tmp_path):
    path = write(tmp_path / "s.toml", SMALL_SWEEP)
    out = str(tmp_path / "out")
    sweep = subprocess.Popen(sweep_command(path, "--out", out, "--workers", "1"),
                             stderr=subprocess.PIPE, text=True)
    for line in sweep.stderr:
        if line.startswith("cell "):
            sweep.send_signal(signal.SIGINT)
            break
    rest = sweep.stderr.read()
    assert sweep.wait(timeout=120) == 130, rest
    finished = [r for r in cell_rows(out) if r["status"] == "ok"]
    assert 1 <= len(finished) < 12
    again = run_sweep(path, "--out", out, "--workers", "1", timeout=600)
    assert again.returncode == 0, again.stderr
    assert f"{len(finished)} finished before, {12 - len(finished)} to run" in again.stderr
    assert len(cell_rows(out)) == 12


def test_nees_columns_come_from_the_summarys_consistency():
    from dynslam._sweep_cells import summary_columns
    summary = {"termination": "convergence", "steps": 3, "iterations": 3, "initial_cost": 2.0,
               "final_cost": 1.0, "time_s": {"total": 0.5, "linear_solve": 0.2},
               "consistency": {"camera": {"count": 30, "mean": 5.5},
                               "object_motion": {"count": 0, "mean": 0.0}}}
    columns = summary_columns(summary)
    assert columns["camera_nees"] == 5.5
    assert columns["object_motion_nees"] is None  # nothing measured is not a NEES of 0
    assert columns["object_pose_nees"] is None
    assert columns["camera_mean_rot_deg"] is None  # no metrics without ground truth


def test_a_results_database_of_an_older_schema_gains_the_new_columns(tmp_path):
    from dynslam._sweep_results import NAMES, Results
    path = str(tmp_path / "results.sqlite")
    with sqlite3.connect(path) as connection:  # the first schema, before weak_directions
        connection.execute("CREATE TABLE cells (scene TEXT NOT NULL, seed INTEGER NOT NULL, "
                           "formulation TEXT NOT NULL, options TEXT NOT NULL, status TEXT NOT NULL, "
                           "PRIMARY KEY (scene, seed, formulation, options))")
        connection.execute("INSERT INTO cells VALUES ('0003', 1, 'wc', 'default', 'ok')")
    results = Results(path)
    results.record({"scene": "0003", "seed": 2, "formulation": "wc", "options": "default",
                    "status": "ok", "weak_directions": 0})
    rows = results.rows()
    results.close()
    assert [r["seed"] for r in rows] == [1, 2] and set(rows[0]) == set(NAMES)
    assert rows[0]["weak_directions"] is None and rows[1]["weak_directions"] == 0


def test_a_results_database_of_before_simulation_sets_has_them_all_default(tmp_path):
    from dynslam._sweep_results import Results
    path = str(tmp_path / "results.sqlite")
    with sqlite3.connect(path) as connection:  # the key before simulation sets
        connection.execute("CREATE TABLE cells (scene TEXT NOT NULL, seed INTEGER NOT NULL, "
                           "formulation TEXT NOT NULL, options TEXT NOT NULL, status TEXT NOT NULL, "
                           "final_cost REAL, PRIMARY KEY (scene, seed, formulation, options))")
        connection.execute("INSERT INTO cells VALUES ('0003', 1, 'wc', 'default', 'ok', 2.5)")
    results = Results(path)
    results.record({"scene": "0003", "seed": 1, "formulation": "wc", "options": "default",
                    "simulate": "pixel_2", "status": "ok", "final_cost": 7.0})
    rows = results.rows()
    assert results.finished() == {("0003", 1, "wc", "default", "default"),
                                  ("0003", 1, "wc", "default", "pixel_2")}
    results.close()
    assert [(r["simulate"], r["final_cost"]) for r in rows] == [("default", 2.5), ("pixel_2", 7.0)]


SIMULATION_SWEEP = """
scenes = ["synthetic"]
frames = "0:12"
seeds = [1, 2, 3, 4, 5, 6]
formulations = ["wc", "oc_b"]
[simulate.default]
[simulate.pixel_2]
pixel_sigma = 2.0
[simulate.pixel_4]
pixel_sigma = 4.0
"""


def test_simulation_sets_reach_the_simulator_and_the_report(tmp_path):
    out = str(tmp_path / "out")
    result = run_sweep(write(tmp_path / "s.toml", SIMULATION_SWEEP), "--out", out, "--workers",
                       "2", timeout=600)
    assert result.returncode == 0, result.stderr
    rows = cell_rows(out)
    assert len(rows) == 36 and all(r["status"] == "ok" for r in rows)
    assert {r["simulate"] for r in rows} == {"default", "pixel_2", "pixel_4"}
    frontends = {}
    for suffix in ("", "_pixel_2", "_pixel_4"):
        with open(os.path.join(out, "cells", f"synthetic_s1{suffix}", "frontend.g2o"), "rb") as f:
            frontends[suffix] = f.read()
    assert len(set(frontends.values())) == 3  # each set its own front end
    # The same seed and settings give the same file as `dynslam simulate` run by hand.
    subprocess.run([CLI, "simulate", "--synthetic", "--seed", "1", "--frames", "0:12",
                    "--pixel-sigma=2.0", "--out", str(tmp_path / "by_hand")], check=True,
                   capture_output=True)
    by_hand = (tmp_path / "by_hand.g2o").read_bytes()
    strip = lambda text: b"\n".join(l for l in text.splitlines() if not l.startswith(b"# arguments"))
    assert strip(by_hand) == strip(frontends["_pixel_2"])
    wc = {r["simulate"]: r for r in rows if r["seed"] == 1 and r["formulation"] == "wc"}
    assert wc["pixel_4"]["cell_dir"] == os.path.join("cells", "synthetic_s1_pixel_4", "wc")
    with open(os.path.join(out, "report.md")) as f:
        report = f.read()
    assert "## Sensitivity to the simulator's settings" in report
    assert "| default | pixel_4 | pixel_sigma = 4.0 | oc_b |" in report
    assert os.path.isfile(os.path.join(out, "report", "sensitivity_pixel_sigma.png"))
    with open(os.path.join(out, "report", "paired.csv")) as f:
        paired = f.read()
    assert "pixel_4,default,oc_b,wc,object_motion_mean_rot_deg,6," in paired


def test_a_second_sweep_in_the_same_directory_is_refused(tmp_path):
    import fcntl
    path = write(tmp_path / "s.toml", SMALL_SWEEP)
    out = tmp_path / "out"
    out.mkdir()
    with open(out / "sweep.lock", "a+") as held:  # as a running sweep holds it
        fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
        result = run_sweep(path, "--out", str(out))
    assert result.returncode == 2 and "in use by another sweep" in result.stderr
    assert not (out / "results.sqlite").exists()
