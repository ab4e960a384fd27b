"""The Python module against the command line and the files it writes (run by ctest as
`python`; needs PYTHONPATH=<build>/python and DYNSLAM_CLI=<the dynslam binary>)."""
import json
import os
import subprocess

import numpy as np
import pytest

import dynslam

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
SCENE = os.path.join(ROOT, "data", "reference", "synthetic")
GT = os.path.join(SCENE, "gt.txt")


def graph_path(formulation):
    return os.path.join(SCENE, "graphs", formulation + ".g2o")


@pytest.fixture(scope="module")
def cli_solve(tmp_path_factory):
    """`dynslam solve` of the synthetic oc_b graph with ground truth: its summary.json."""
    out = tmp_path_factory.mktemp("cli") / "oc_b"
    subprocess.run([os.environ["DYNSLAM_CLI"], "solve", graph_path("oc_b"), "--gt", GT,
                    "--out", str(out)], check=True, capture_output=True)
    with open(out / "summary.json") as f:
        return json.load(f)


def test_read_write_round_trip(tmp_path):
    graph = dynslam.read_graph(graph_path("wc"))
    dynslam.write_graph(graph, str(tmp_path / "copy.g2o"))
    again = dynslam.read_graph(str(tmp_path / "copy.g2o"))
    assert (again.num_vertices, again.num_edges) == (graph.num_vertices, graph.num_edges)
    assert again.edges_by_kind == graph.edges_by_kind
    for role in ("camera", "dynamic_point", "motion"):
        a, b = graph.vertices(role), again.vertices(role)
        assert np.array_equal(a["id"], b["id"])
        assert np.array_equal(a["value"], b["value"])  # bit-exact (SPEC §1)


def test_numpy_shapes():
    graph = dynslam.read_graph(graph_path("oc_b"))
    cameras = graph.vertices("camera")
    assert cameras["value"].shape == (len(cameras["id"]), 7) and cameras["value"].dtype == np.float64
    assert cameras["id"].dtype == np.int64
    points = graph.vertices("object_point")
    assert points["value"].shape == (len(points["id"]), 3)
    assert np.allclose(np.linalg.norm(cameras["value"][:, 3:], axis=1), 1)  # unit quaternions
    report = dynslam.solve(graph, max_iterations=3)
    columns = report.convergence
    assert set(columns) == {"step", "iteration", "lambda", "cost", "trial_cost", "accepted",
                            "time_s"}
    assert columns["cost"].shape == (report.steps,) and columns["accepted"].dtype == np.bool_


def test_build_matches_the_reference_graph_counts():
    frontend = dynslam.read_graph(os.path.join(SCENE, "frontend.g2o"))
    built = dynslam.build(frontend, "oc_b", GT, object_init="align")
    reference = dynslam.read_graph(graph_path("oc_b"))
    assert built.edges_by_kind == reference.edges_by_kind
    assert built.num_vertices == reference.num_vertices
    assert built.formulation == "oc_b"


def test_hybrid_builds_the_reference_graph_and_solves_with_world_information():
    frontend = dynslam.read_graph(os.path.join(SCENE, "frontend.g2o"))
    built = dynslam.build(frontend, "hy", GT)
    reference = dynslam.read_graph(os.path.join(ROOT, "data", "reference_hybrid", "synthetic",
                                                "graphs", "hy.g2o"))
    assert dynslam.FORMULATIONS[-1] == "hy"
    assert built.edges_by_kind == reference.edges_by_kind
    assert built.formulation == "hy"
    world = dynslam.build(frontend, "hy", GT, hybrid_smoothing_info="world")
    assert world.edges_by_kind == built.edges_by_kind
    with pytest.raises(ValueError):
        dynslam.build(frontend, "hy", GT, hybrid_smoothing_info="body")
    report = dynslam.solve(world, max_iterations=3)
    assert report.final_cost < report.initial_cost


def test_solve_reaches_the_cli_final_cost(cli_solve):
    report = dynslam.solve(dynslam.read_graph(graph_path("oc_b")))
    assert report.usable and report.termination == cli_solve["termination"]
    assert report.steps == cli_solve["steps"]
    assert report.extrapolations == cli_solve["extrapolations"]
    assert report.final_cost == pytest.approx(cli_solve["final_cost"], rel=1e-12)


def test_tight_rule_is_remaining_chi2_zero_without_extrapolation(tmp_path):
    out = tmp_path / "tight"
    subprocess.run([os.environ["DYNSLAM_CLI"], "solve", graph_path("oc_b"), "--tolerances",
                    "tight", "--out", str(out)], check=True, capture_output=True)
    with open(out / "summary.json") as f:
        cli = json.load(f)
    assert cli["solver"]["remaining_chi2"] == 0 and cli["solver"]["extrapolation"] is False
    report = dynslam.solve(dynslam.read_graph(graph_path("oc_b")), tolerances="tight")
    spelled_out = dynslam.solve(dynslam.read_graph(graph_path("oc_b")), remaining_chi2=0,
                                extrapolation=False)
    assert spelled_out.summary()["solver"] == report.summary()["solver"] == cli["solver"]
    assert spelled_out.steps == report.steps
    assert report.steps == cli["steps"] > dynslam.solve(
        dynslam.read_graph(graph_path("oc_b"))).steps
    assert report.final_cost == pytest.approx(cli["final_cost"], rel=1e-12)


def test_metrics_equal_the_summary(cli_solve):
    report = dynslam.solve(dynslam.read_graph(graph_path("oc_b")))
    ours = dynslam.metrics(report.graph, GT)
    assert ours.keys() == cli_solve["metrics"].keys()
    for family in ("camera", "object_motion", "object_pose"):
        for key, value in cli_solve["metrics"][family].items():
            if isinstance(value, float):
                assert ours[family][key] == pytest.approx(value, rel=1e-9, abs=1e-12)
            elif not isinstance(value, dict):
                assert ours[family][key] == value


def test_errors_carry_file_and_line(tmp_path):
    bad = tmp_path / "bad.g2o"
    bad.write_text("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_TRACKXYZ 1 0 zero 0\n")
    with pytest.raises(dynslam.Error) as raised:
        dynslam.read_graph(str(bad))
    assert raised.value.file == str(bad) and raised.value.line == 2
    assert "field 3 'zero' is not a number" in str(raised.value)
    with pytest.raises(TypeError):
        dynslam.solve(dynslam.read_graph(graph_path("wc")), no_such_option=1)
    with pytest.raises(ValueError):
        dynslam.solve(dynslam.read_graph(graph_path("wc")), minimizer="newton")


def test_simulate_and_compare():
    frontend, gt = dynslam.simulate(synthetic=True, synthetic_frames=12, seed=1)
    results = dynslam.compare(frontend, gt, formulations=("wc", "oc_c"), max_iterations=50)
    assert set(results) == {"wc", "oc_c"}
    for result in results.values():
        assert result["report"].usable
        assert result["metrics"]["camera"]["pairs"] == 11
    without_truth = dynslam.compare(frontend, formulations=("wc",), max_iterations=5)
    assert without_truth["wc"]["metrics"] is None


def test_example_compares_and_plots(tmp_path):
    example = os.path.join(ROOT, "examples", "compare_formulations.py")
    out = tmp_path / "convergence.png"
    result = subprocess.run(["/usr/bin/python3", example, "--frames", "20", "--out", str(out)],
                            capture_output=True, text=True, env=dict(os.environ))
    assert result.returncode == 0, result.stderr
    assert out.stat().st_size > 1000
    for name in dynslam.FORMULATIONS:
        assert name in result.stdout


def test_ctrl_c_stops_the_solve_and_keeps_its_report(tmp_path):
    """SIGINT during a long solve: KeyboardInterrupt after the current step, with the report."""
    script = tmp_path / "interrupt.py"
    script.write_text(
        "import os, signal, threading, dynslam\n"
        "frontend, gt = dynslam.simulate(synthetic=True, synthetic_frames=400, seed=1)\n"
        "graph = dynslam.build(frontend, 'wc', gt)\n"
        "threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()\n"
        "try:\n"
        "    dynslam.solve(graph)\n"
        "    print('finished')\n"
        "except KeyboardInterrupt as interrupt:\n"
        "    r = interrupt.report\n"
        "    print('interrupted', r.termination, r.steps, r.usable, r.final_cost < r.initial_cost)\n")
    result = subprocess.run(["/usr/bin/python3", str(script)], capture_output=True, text=True,
                            env=dict(os.environ), timeout=300)
    assert result.returncode == 0, result.stderr
    words = result.stdout.split()
    assert words[:2] == ["interrupted", "interrupted"], result.stdout
    assert 0 < int(words[2]) < 11 and words[3:] == ["True", "True"], result.stdout


def test_gauge_moves_option_matches_the_cli(tmp_path):
    out = tmp_path / "moves"
    subprocess.run([os.environ["DYNSLAM_CLI"], "solve", graph_path("oc_b"), "--gauge-moves", "on",
                    "--out", str(out)], check=True, capture_output=True)
    with open(out / "summary.json") as f:
        cli = json.load(f)
    assert cli["solver"]["gauge_moves"] is True
    report = dynslam.solve(dynslam.read_graph(graph_path("oc_b")), gauge_moves=True)
    # This graph makes no move, so the counts alone would not show the option reached the solver.
    assert report.summary()["solver"]["gauge_moves"] is True
    assert report.gauge_moves == cli["gauge_moves"]
    assert report.steps == cli["steps"]
    assert report.final_cost == pytest.approx(cli["final_cost"], rel=1e-12)


def test_start_from_wc_matches_the_cli(tmp_path):
    """build(..., start=wc solution) writes the file `dynslam build --start` writes."""
    wc = dynslam.solve(dynslam.read_graph(graph_path("wc"))).graph
    dynslam.write_graph(wc, str(tmp_path / "wc.g2o"))
    frontend = os.path.join(SCENE, "frontend.g2o")
    subprocess.run([os.environ["DYNSLAM_CLI"], "build", frontend, "--formulation", "oc_a",
                    "--gt", GT, "--start", str(tmp_path / "wc.g2o"), "--out",
                    str(tmp_path / "cli.g2o")], check=True, capture_output=True)
    front = dynslam.read_graph(frontend)
    started = dynslam.build(front, "oc_a", GT, start=wc)
    dynslam.write_graph(started, str(tmp_path / "py.g2o"))
    assert (tmp_path / "py.g2o").read_text() == (tmp_path / "cli.g2o").read_text()
    default = dynslam.build(front, "oc_a", GT)
    dynslam.write_graph(default, str(tmp_path / "default.g2o"))
    assert (tmp_path / "py.g2o").read_text() != (tmp_path / "default.g2o").read_text()
    with pytest.raises(dynslam.Error):
        dynslam.build(front, "hy", GT, start=wc)
    with pytest.raises(TypeError):
        dynslam.build(front, "oc_a", GT, start=str(tmp_path / "wc.g2o"))
    results = dynslam.compare(front, GT, formulations=("wc", "oc_a"), start="wc")
    assert results["oc_a"]["report"].initial_cost == pytest.approx(
        dynslam.solve(started, max_iterations=1).initial_cost, rel=1e-12)
    with pytest.raises(ValueError):
        dynslam.compare(front, GT, formulations=("oc_a",), start="wc")


def test_concurrent_solves_equal_serial_ones():
    """Eight solves on eight Python threads (the GIL is released while solving) end exactly
    where the same solves end one after another (issue 44: a BLAS unsafe for concurrent callers
    made them differ)."""
    import threading
    graphs = []
    for seed in (1, 2):
        frontend, gt = dynslam.simulate(synthetic=True, seed=seed)
        graphs += [dynslam.build(frontend, f, gt) for f in ("wc", "oc_a", "oc_b", "oc_c")]

    def outcome(report):
        values = [report.graph.vertices(role)["value"] for role in ("camera", "motion")]
        return report.final_cost, report.steps, values

    serial = [outcome(dynslam.solve(graph)) for graph in graphs]
    for _ in range(3):
        concurrent = [None] * len(graphs)

        def run(i):
            concurrent[i] = outcome(dynslam.solve(graphs[i]))

        threads = [threading.Thread(target=run, args=(i,)) for i in range(len(graphs))]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        for (cost, steps, values), (cost2, steps2, values2) in zip(serial, concurrent):
            assert (cost, steps) == (cost2, steps2)
            assert all(np.array_equal(a, b) for a, b in zip(values, values2))


def test_covariances_as_arrays_and_their_errors(tmp_path):
    report = dynslam.solve(dynslam.read_graph(graph_path("oc_b")))
    cameras = report.covariance(kinds="cameras")
    ids = report.graph.vertices("camera")["id"]
    assert sorted(cameras) == sorted(int(i) for i in ids)
    block = cameras[int(ids[-1])]
    assert block.shape == (6, 6) and np.allclose(block, block.T)
    assert np.all(np.linalg.eigvalsh(block) > 0)
    # The same numbers as the command line's covariances.csv, to the last digit.
    out = tmp_path / "cli"
    subprocess.run([os.environ["DYNSLAM_CLI"], "solve", graph_path("oc_b"), "--out", str(out),
                    "--covariance", "cameras"], check=True, capture_output=True)
    with open(out / "covariances.csv") as f:
        row = [line for line in f if line.startswith(f"{int(ids[-1])},")][0].split(",")
    assert row[1:3] == ["camera", "6"]
    assert [float(x) for x in row[3:]] == [block[r, c] for r in range(6) for c in range(r, 6)]
    with pytest.raises(ValueError, match="poses"):
        report.covariance(kinds="poses")
    pose_graph = os.path.join(ROOT, "data", "reference", "posegraph_parking-garage", "graphs",
                              "pose_graph.g2o")
    held = dynslam.solve(dynslam.read_graph(pose_graph), fix_first=True, max_iterations=2)
    with pytest.raises(ValueError, match="held constant"):
        held.covariance(ids=[0])  # the smallest-id pose, which fix_first holds


def test_the_gtsam_backend_or_how_to_build_it():
    graph = dynslam.read_graph(graph_path("wc"))
    with pytest.raises(ValueError, match="known: ceres, gtsam"):
        dynslam.solve(graph, backend="g2o")
    try:
        report = dynslam.solve(graph, backend="gtsam:tight")
    except ValueError as error:  # a build without GTSAM says how to get it
        assert "scripts/build_gtsam" in str(error)
        return
    ceres = dynslam.solve(graph, tolerances="tight")
    assert report.final_cost == pytest.approx(ceres.final_cost, rel=1e-6)


def test_a_singular_information_matrix_names_its_weak_directions(tmp_path):
    import lzma
    compressed = os.path.join(ROOT, "data", "reference", "kitti_0003", "graphs", "oc_a.g2o.xz")
    path = tmp_path / "oc_a.g2o"
    with lzma.open(compressed) as f:
        path.write_bytes(f.read())
    report = dynslam.solve(dynslam.read_graph(str(path)))
    with pytest.raises(np.linalg.LinAlgError, match="singular along"):
        report.covariance()


def test_version_paths_pickling_and_reprs(tmp_path):
    import pathlib
    import pickle
    assert dynslam.__version__.count(".") == 2
    graph = dynslam.read_graph(pathlib.Path(graph_path("oc_b")))
    assert repr(graph) == f"<dynslam.Graph oc_b, {graph.num_vertices} vertices, {graph.num_edges} edges>"
    dynslam.write_graph(graph, tmp_path / "copy.g2o")  # a path-like to write to
    again = pickle.loads(pickle.dumps(graph))
    assert (again.num_vertices, again.num_edges) == (graph.num_vertices, graph.num_edges)
    for role in ("camera", "object_pose", "object_point"):
        assert np.array_equal(again.vertices(role)["value"], graph.vertices(role)["value"])
    gt = dynslam.read_ground_truth(pathlib.Path(GT))
    gt_again = pickle.loads(pickle.dumps(gt))
    assert repr(gt_again) == repr(gt) == f"<dynslam.GroundTruth {gt.num_cameras} cameras, {gt.num_object_poses} object poses>"
    report = dynslam.solve(again, max_iterations=5)
    # The metrics of a pickled ground truth are those of the file's, to the last digit.
    assert dynslam.metrics(report.graph, gt_again) == dynslam.metrics(report.graph, GT)
    assert repr(report).startswith("<dynslam.SolveReport no_convergence, 5 steps, cost ")


@pytest.mark.parametrize("options, error, words", [
    ({"max_iterations": "5"}, TypeError, "max_iterations: expected int, got str"),
    ({"extrapolation": 1}, TypeError, "extrapolation: expected bool, got int 1"),
    ({"extrapolate": 1}, TypeError, "extrapolation: expected bool"),  # the earlier spelling
    ({"minimizer": 3}, TypeError, "minimizer: expected str"),
    ({"minimizer": "newton"}, ValueError, "minimizer: 'newton' is not one of auto|lm|dogleg"),
    ({"remaining_chi2": -1.0}, ValueError, "remaining_chi2: '-1' is not a number from 0"),
    ({"robust": "point=tukey:1"}, ValueError, "robust: unknown kernel 'tukey'"),
    ({"tolerances": "tight", "extrapolation": True}, ValueError,
     "tolerances tight sets extrapolation off; give one of them"),
    ({"max-iterations": 5}, TypeError, "unknown option 'max-iterations'"),
    ({"no_such_option": 1}, TypeError, "unknown option 'no_such_option'"),
])
def test_bad_options_name_themselves(options, error, words):
    with pytest.raises(error, match=words):
        dynslam.solve(dynslam.read_graph(graph_path("wc")), **options)


def test_missing_files_are_file_not_found(tmp_path):
    for read in (dynslam.read_graph, dynslam.read_ground_truth):
        with pytest.raises(FileNotFoundError) as raised:
            read(tmp_path / "absent")
        assert raised.value.filename == str(tmp_path / "absent")
    with pytest.raises(TypeError):
        dynslam.read_graph(42)


def test_uncertainty_plot_of_a_solve_with_covariances(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "wc"
    subprocess.run([os.environ["DYNSLAM_CLI"], "solve", graph_path("wc"), "--gt", GT, "--out",
                    str(out), "--covariance", "cameras,motions"], check=True, capture_output=True)
    script = os.path.join(ROOT, "scripts", "plot_uncertainty.py")
    result = subprocess.run(["/usr/bin/python3", script, str(out), "--gt", GT, "--object", "1"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert (out / "uncertainty.png").stat().st_size > 10000
    missing = subprocess.run(["/usr/bin/python3", script, str(tmp_path), "--gt", GT],
                             capture_output=True, text=True)
    assert missing.returncode != 0 and "no solution.g2o" in missing.stderr


def command_flags(command):
    """The options `dynslam COMMAND --help` lists, spelled as Python keywords."""
    text = subprocess.run([os.environ["DYNSLAM_CLI"], command, "--help"], check=True,
                          capture_output=True, text=True).stdout
    return {line.split()[0][2:].replace("-", "_") for line in text.splitlines()
            if line.startswith("  --")}


def documented_options(function):
    """The options a docstring lists ("    name (type, default value): help")."""
    return {line.split()[0] for line in function.__doc__.splitlines()
            if line.startswith("    ") and "(" in line}


def test_docstrings_list_every_option():
    """help(dynslam.solve), help(dynslam.build) and help(dynslam.simulate) name every option
    with its default; the names are the option tables' (the flags with '_' for '-')."""
    documented = documented_options(dynslam.solve)
    assert {"remaining_chi2", "tolerances", "robust", "max_time", "dsc_released_lm"} <= documented
    assert documented <= command_flags("solve")  # every solver option is a flag of `solve` too
    assert "    remaining_chi2 (float, default 0.01" in dynslam.solve.__doc__
    assert "    extrapolation (bool, default True" in dynslam.solve.__doc__
    assert {"object_init", "hybrid_smoothing_info", "kinematic_sigma"} <= documented_options(
        dynslam.build)
    simulate_documented = documented_options(dynslam.simulate)
    assert {"frames", "seed", "synthetic", "noise", "static_points"} <= simulate_documented
    # every flag of `dynslam simulate` but the command's own (where to read and write, density,
    # the sweep's check of a simulation set)
    assert command_flags("simulate") - simulate_documented == {"help", "kitti", "seq", "density",
                                                               "out", "check_options"}


def test_robust_kernels_as_text_reach_the_solver():
    report = dynslam.solve(dynslam.read_graph(graph_path("wc")), robust="point=huber:1.345",
                           max_iterations=3)
    assert report.summary()["solver"]["robust"] == "point=huber:1.345"


def test_simulate_finds_the_embedded_kitti_data_from_anywhere(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("DYNSLAM_KITTI", raising=False)
    assert os.path.isdir(os.path.join(dynslam.embedded_kitti_dir(), "label_02"))
    frontend, gt = dynslam.simulate(sequence="0003", frames="0:5", seed=1)
    assert gt.num_cameras == 5
    with pytest.raises(ValueError, match="frames: '5:2' is not A:B"):
        dynslam.simulate(sequence="0003", frames="5:2")
    with pytest.raises(TypeError, match="unknown option 'last_frame'"):
        dynslam.simulate(sequence="0003", last_frame=5)


def test_values_out_of_and_into_arrays():
    """vertices() and with_values() are inverses; the edited graph solves from the new values."""
    graph = dynslam.read_graph(graph_path("oc_b"))
    cameras = graph.vertices("camera")
    moved = cameras["value"].copy()
    moved[:, 0] += 0.5  # every camera half a metre along x
    edited = graph.with_values(cameras["id"], moved)
    assert np.allclose(edited.vertices("camera")["value"], moved)
    assert np.array_equal(graph.vertices("camera")["value"], cameras["value"])  # a copy
    assert dynslam.solve(edited).initial_cost > dynslam.solve(graph).initial_cost
    again = edited.with_values(cameras["id"], cameras["value"])
    assert np.array_equal(again.vertices("camera")["value"], cameras["value"])
    points = graph.vertices("static_point")
    with pytest.raises(ValueError, match="is a point: give 3 columns"):
        graph.with_values(points["id"][:1], moved[:1])
    with pytest.raises(ValueError, match="is not a vertex"):
        graph.with_values([123456789], moved[:1])


def test_numpy_scalars_are_options_of_their_kind():
    graph = dynslam.read_graph(graph_path("wc"))
    report = dynslam.solve(graph, max_iterations=np.int64(3), remaining_chi2=np.float32(0.5),
                           extrapolation=np.bool_(False))
    solver = report.summary()["solver"]
    assert solver["max_iterations"] == 3 and solver["remaining_chi2"] == 0.5
    assert solver["extrapolation"] is False
    with pytest.raises(TypeError, match="max_iterations: expected int, got float64"):
        dynslam.solve(graph, max_iterations=np.float64(3))
    with pytest.raises(TypeError, match="remaining_chi2: expected float, got bool_"):
        dynslam.solve(graph, remaining_chi2=np.bool_(True))


def file_edges(path, tag):
    """The edges of `tag` as the file writes them: rows of numbers after the tag (a reader
    independent of the module, for checking its arrays)."""
    with open(path) as f:
        return [[float(x) for x in line.split()[1:]] for line in f if line.split()[:1] == [tag]]


def upper_triangle(matrix):
    return [matrix[r][c] for r in range(len(matrix)) for c in range(r, len(matrix))]


def test_edges_as_arrays_in_the_files_order():
    """edges(tag) gives each field of the tag as a column, measurements and information in the
    file's order (g2o: translation first), as a text reader of the file finds them."""
    path = os.path.join(SCENE, "frontend.g2o")
    graph = dynslam.read_graph(path)
    odometry = graph.edges("EDGE_SE3:QUAT")
    rows = file_edges(path, "EDGE_SE3:QUAT")
    assert sorted(odometry) == ["a", "b", "information", "measurement"]
    assert odometry["information"].shape == (len(rows), 6, 6)
    assert np.diag(odometry["information"][0]).tolist() == [2500] * 3 + [250000] * 3
    for i, row in enumerate(rows):
        assert [odometry["a"][i], odometry["b"][i]] == row[:2]
        assert odometry["measurement"][i].tolist() == row[2:9]
        assert upper_triangle(odometry["information"][i]) == row[9:]
    tracks = graph.edges("EDGE_SE3_TRACKXYZ")
    assert sorted(tracks) == ["information", "is_dynamic", "measurement", "point", "pose"]
    assert tracks["is_dynamic"].dtype == np.bool_ and tracks["is_dynamic"].any()
    assert tracks["information"].shape[1:] == (3, 3)
    with pytest.raises(ValueError, match="unknown edge tag 'EDGE_NOPE'.*EDGE_SE3_MOTION"):
        graph.edges("EDGE_NOPE")


@pytest.mark.parametrize("name", ["frontend", "wc", "oc_b"])
def test_graph_from_its_arrays_is_the_same_graph(name, tmp_path):
    """Graph.from_arrays(**graph.arrays()) writes the same file, byte for byte."""
    path = os.path.join(SCENE, "frontend.g2o") if name == "frontend" else graph_path(name)
    graph = dynslam.read_graph(path)
    arrays = graph.arrays()
    assert set(arrays) == {"vertices", "edges", "formulation"}
    again = dynslam.Graph.from_arrays(**arrays)
    dynslam.write_graph(graph, tmp_path / "a.g2o")
    dynslam.write_graph(again, tmp_path / "b.g2o")
    assert (tmp_path / "a.g2o").read_bytes() == (tmp_path / "b.g2o").read_bytes()


def test_a_pose_graph_built_from_arrays_solves():
    """Three cameras, a prior and two odometry edges from NumPy: the file the graph writes has
    the information in g2o's order, and the solve moves the cameras onto the measurements."""
    identity = np.array([0, 0, 0, 0, 0, 0, 1.0])
    step = np.array([1.0, 0, 0, 0, 0, 0, 1])
    information = np.diag([1.0, 2, 3, 4, 5, 6])  # file order: translation, then rotation
    graph = dynslam.Graph.from_arrays(
        vertices={"camera": {"id": [0, 1, 2], "frame": [0, 1, 2],
                             "value": [identity, identity, identity]}},
        edges={"EDGE_SE3_PRIOR": {"id": [0], "measurement": [identity],
                                  "information": [information]},
               "EDGE_SE3:QUAT": {"a": [0, 1], "b": [1, 2], "measurement": [step, step],
                                 "information": [information, information]}})
    assert graph.edges_by_kind["odometry"] == 2 and graph.edges_by_kind["prior"] == 1
    assert upper_triangle(graph.edges("EDGE_SE3:QUAT")["information"][0]) == \
        upper_triangle(information.tolist())
    report = dynslam.solve(graph)
    assert report.final_cost < 1e-20
    assert np.allclose(report.graph.vertices("camera")["value"][:, 0], [0, 1, 2], atol=1e-9)


def test_bad_arrays_name_the_table_row_and_column():
    pose = [0, 0, 0, 0, 0, 0, 1.0]
    cameras = {"camera": {"id": [0, 1], "frame": [0, 1], "value": [pose, pose]}}
    odometry = {"a": [0], "b": [7], "measurement": [pose], "information": [np.eye(6)]}
    with pytest.raises(dynslam.Error, match=r"edges\['EDGE_SE3:QUAT'\] row 0: .*7"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": odometry})
    with pytest.raises(ValueError, match=r"edges\['EDGE_SE3:QUAT'\]: no column 'information'"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {
            k: v for k, v in odometry.items() if k != "information"}})
    with pytest.raises(ValueError, match=r"edges\['EDGE_SE3:QUAT'\]: unknown column 'c'"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {**odometry, "c": [1]}})
    with pytest.raises(ValueError, match=r"edges\['EDGE_SE3:QUAT'\]\['b'\]: 2 rows, 'a' has 1"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {**odometry, "b": [1, 1]}})
    with pytest.raises(ValueError, match=r"\['information'\]: shape \(1, 3, 3\), wanted \(1, 6, 6\)"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {
            **odometry, "information": [np.eye(3)]}})
    asymmetric = np.eye(6)
    asymmetric[0, 1] = 1
    with pytest.raises(ValueError, match=r"\['information'\] row 0 is not symmetric"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {
            **odometry, "b": [1], "information": [asymmetric]}})
    with pytest.raises(TypeError, match=r"\['a'\]: integers wanted, not float64"):
        dynslam.Graph.from_arrays(vertices=cameras, edges={"EDGE_SE3:QUAT": {
            **odometry, "a": [0.5]}})
    with pytest.raises(ValueError, match=r"unknown vertex table 'cameras'.*camera"):
        dynslam.Graph.from_arrays(vertices={"cameras": cameras["camera"]}, edges={})
    with pytest.raises(ValueError, match=r"vertices\['camera'\]: no column 'frame'"):
        dynslam.Graph.from_arrays(vertices={"camera": {"id": [0], "value": [pose]}}, edges={})
    with pytest.raises(ValueError, match=r"vertices\['camera'\]\['object'\]: a camera has no "):
        dynslam.Graph.from_arrays(vertices={"camera": {**cameras["camera"], "object": [3, 3]}},
                                  edges={})
    with pytest.raises(dynslam.Error, match=r"vertices\['camera'\] row 1: .*not finite|nan"):
        dynslam.Graph.from_arrays(vertices={"camera": {**cameras["camera"],
                                                       "value": [pose, [np.nan] * 7]}}, edges={})
