"""dynslam: Dynamic SLAM back ends on Ceres Solver, from Python (docs/PYTHON.md).

    import dynslam
    frontend, gt = dynslam.simulate("data/kitti_tracking", "0003", last_frame=60, seed=1)
    graph = dynslam.build(frontend, "oc_b", gt)
    report = dynslam.solve(graph, max_iterations=100)
    print(report.final_cost, report.steps, dynslam.metrics(report.graph, gt)["object_motion"])

Poses are arrays [tx ty tz qx qy qz qw]; errors are dynslam.Error with .file and .line.
"""
from ._dynslam import (FORMULATIONS, Error, Graph, GroundTruth, SolveReport, build, metrics,
                       read_graph, read_ground_truth, simulate, solve, write_graph)

__all__ = ["Error", "FORMULATIONS", "Graph", "GroundTruth", "SolveReport", "build", "compare",
           "metrics", "read_graph", "read_ground_truth", "simulate", "solve", "write_graph"]


def compare(frontend, gt=None, formulations=FORMULATIONS, build_options=None, **solver_options):
    """Every formulation built from one front end (identical data) and solved the same way, as
    `dynslam compare` does. Returns {formulation: {"report": SolveReport, "metrics": dict or
    None}}; metrics need ground truth (a GroundTruth or a path)."""
    results = {}
    for formulation in formulations:
        graph = build(frontend, formulation, gt, **(build_options or {}))
        report = solve(graph, **solver_options)
        results[formulation] = {
            "report": report,
            "metrics": metrics(report.graph, gt) if gt is not None else None,
        }
    return results
