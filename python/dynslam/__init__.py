"""dynslam: Dynamic SLAM back ends on Ceres Solver, from Python (docs/PYTHON.md).

    import dynslam
    frontend, gt = dynslam.simulate("data/kitti_tracking", "0003", last_frame=60, seed=1)
    graph = dynslam.build(frontend, "oc_b", gt)
    report = dynslam.solve(graph, max_iterations=100)
    print(report.final_cost, report.steps, dynslam.metrics(report.graph, gt)["object_motion"])

Poses are arrays [tx ty tz qx qy qz qw]; errors are dynslam.Error with .file and .line.
"""
from ._version import __version__
from ._dynslam import (FORMULATIONS, Error, Graph, GroundTruth, SolveReport, build, metrics,
                       read_graph, read_ground_truth, simulate, solve, write_graph)

__all__ = ["__version__", "Error", "FORMULATIONS", "Graph", "GroundTruth", "SolveReport", "build", "compare",
           "metrics", "read_graph", "read_ground_truth", "simulate", "solve", "write_graph"]


def compare(frontend, gt=None, formulations=FORMULATIONS, build_options=None, start="frontend",
            **solver_options):
    """Every formulation built from one front end (identical data) and solved the same way, as
    `dynslam compare` does. Returns {formulation: {"report": SolveReport, "metrics": dict or
    None}}; metrics need ground truth (a GroundTruth or a path). start="wc": oc_a, oc_b and oc_c
    start from wc's solution (SPEC §3.5; wc must come first in `formulations`)."""
    if start not in ("frontend", "wc"):
        raise ValueError("start must be 'frontend' or 'wc', not %r" % (start,))
    if start == "wc" and (not formulations or formulations[0] != "wc"):
        raise ValueError("start='wc': wc must come first in formulations")
    results = {}
    for formulation in formulations:
        started = start == "wc" and formulation in ("oc_a", "oc_b", "oc_c")
        graph = build(frontend, formulation, gt,
                      start=results["wc"]["report"].graph if started else None,
                      **(build_options or {}))
        report = solve(graph, **solver_options)
        results[formulation] = {
            "report": report,
            "metrics": metrics(report.graph, gt) if gt is not None else None,
        }
    return results
