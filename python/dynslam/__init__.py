"""dynslam: Dynamic SLAM back ends on Ceres Solver, from Python (docs/PYTHON.md).

    import dynslam
    frontend, gt = dynslam.simulate("data/kitti_tracking", "0003", last_frame=60, seed=1)
    graph = dynslam.build(frontend, "oc_b", gt)
    report = dynslam.solve(graph, max_iterations=100)
    print(report.final_cost, report.steps, dynslam.metrics(report.graph, gt)["object_motion"])

Poses are arrays [tx ty tz qx qy qz qw]; errors are dynslam.Error with .file and .line.
"""
from ._version import __version__
from ._dynslam import (FORMULATIONS, Error, Graph, GroundTruth, SolveReport, build, compare,
                       metrics, read_graph, read_ground_truth, simulate, solve, write_graph)

__all__ = ["__version__", "Error", "FORMULATIONS", "Graph", "GroundTruth", "SolveReport", "build", "compare",
           "metrics", "read_graph", "read_ground_truth", "simulate", "solve", "write_graph"]

