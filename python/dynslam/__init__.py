"""dynslam: Dynamic SLAM back ends on Ceres Solver, from Python (docs/PYTHON.md).

    import dynslam
    frontend, gt = dynslam.simulate(sequence="0003", frames="0:60", seed=1)
    graph = dynslam.build(frontend, "oc_b", gt)
    report = dynslam.solve(graph, max_iterations=100)
    print(report.final_cost, report.steps, dynslam.metrics(report.graph, gt)["object_motion"])

Poses are arrays [tx ty tz qx qy qz qw]; errors are dynslam.Error with .file and .line.
"""
from ._version import __version__
from . import _dynslam
from ._sweep_tools import embedded_kitti as embedded_kitti_dir
from ._dynslam import (FORMULATIONS, Error, Graph, GroundTruth, SolveReport, build, compare,
                       metrics, read_graph, read_ground_truth, solve, write_graph)


def simulate(kitti_dir=None, sequence=None, **options):
    if kitti_dir is None and sequence is not None and not options.get("synthetic", False):
        kitti_dir = embedded_kitti_dir()
    return _dynslam.simulate(kitti_dir, sequence, **options)


simulate.__doc__ = (_dynslam.simulate.__doc__ or "") + (
    "\n\nkitti_dir: the embedded KITTI data (embedded_kitti_dir()) when not given.")

__all__ = ["__version__", "Error", "FORMULATIONS", "Graph", "GroundTruth", "SolveReport", "build", "compare",
           "embedded_kitti_dir", "metrics", "read_graph", "read_ground_truth", "simulate", "solve", "write_graph"]

