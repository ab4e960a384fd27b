"""dynslam: Dynamic SLAM back ends on Ceres Solver, from Python (docs/PYTHON.md).

    import dynslam
    frontend, gt = dynslam.simulate(sequence="0003", last_frame=60, seed=1)
    graph = dynslam.build(frontend, "oc_b", gt)
    report = dynslam.solve(graph, max_iterations=100)
    print(report.final_cost, report.steps, dynslam.metrics(report.graph, gt)["object_motion"])

Poses are arrays [tx ty tz qx qy qz qw]; errors are dynslam.Error with .file and .line.
"""
import os
import pathlib

from ._version import __version__
from . import _dynslam
from ._dynslam import (FORMULATIONS, Error, Graph, GroundTruth, SolveReport, build, compare,
                       metrics, read_graph, read_ground_truth, solve, write_graph)


def embedded_kitti_dir():
    """The KITTI Tracking ground truth shipped with dynslam (oxts/, label_02/, calib/):
    $DYNSLAM_KITTI, else the installed package's data/kitti_tracking, else the repository's
    data/kitti_tracking above a module in its build tree; None when there is none."""
    package = pathlib.Path(__file__).resolve().parent
    candidates = [os.environ.get("DYNSLAM_KITTI") or None, package / "data" / "kitti_tracking"]
    candidates += [parent / "data" / "kitti_tracking" for parent in package.parents]
    for candidate in candidates:
        if candidate and (pathlib.Path(candidate) / "label_02").is_dir():
            return str(candidate)
    return None


def simulate(kitti_dir=None, sequence=None, synthetic=False, **options):
    if kitti_dir is None and sequence is not None and not synthetic:
        kitti_dir = embedded_kitti_dir()
    return _dynslam.simulate(kitti_dir, sequence, synthetic, **options)


simulate.__doc__ = (_dynslam.simulate.__doc__ or "") + (
    "\n\nkitti_dir: the embedded KITTI data (embedded_kitti_dir()) when not given.")

__all__ = ["__version__", "Error", "FORMULATIONS", "Graph", "GroundTruth", "SolveReport", "build", "compare",
           "embedded_kitti_dir", "metrics", "read_graph", "read_ground_truth", "simulate", "solve", "write_graph"]

