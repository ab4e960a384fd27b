#!/usr/bin/env python3
"""Compare the formulations on one simulated KITTI sequence from Python and plot how each solve
converged (the paper's Fig. 4). Needs the Python module (PYTHONPATH=build/release/python, or
scripts/install_python_module) and matplotlib.

    examples/compare_formulations.py --sequence 0003 --frames 40 --out convergence.png
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import dynslam  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kitti", default=os.path.join(HERE, "..", "data", "kitti_tracking"))
    parser.add_argument("--sequence", default="0003")
    parser.add_argument("--frames", type=int, default=40, help="first N frames")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default="convergence.png")
    args = parser.parse_args()

    frontend, gt = dynslam.simulate(args.kitti, args.sequence, frames=f"0:{args.frames}",
                                    seed=args.seed)
    results = dynslam.compare(frontend, gt)
    print(f"{'formulation':12} {'variables':>9} {'steps':>5} {'final cost':>14} "
          f"{'motion E_r (deg)':>16} {'motion E_t (m)':>14}")
    figure, axes = plt.subplots(figsize=(7, 4))
    for name, result in results.items():
        report, motion = result["report"], result["metrics"]["object_motion"]
        print(f"{name:12} {report.graph.num_vertices:9d} {report.steps:5d} "
              f"{report.final_cost:14.6f} {motion['mean_rot_deg']:16.4f} "
              f"{motion['mean_trans_m']:14.4f}")
        convergence = report.convergence
        accepted = convergence["accepted"]
        axes.semilogy(convergence["time_s"][accepted], convergence["trial_cost"][accepted],
                      marker=".", label=name)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("cost (½χ²)")
    axes.set_title(f"KITTI {args.sequence}, frames 0:{args.frames}, seed {args.seed}")
    axes.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
