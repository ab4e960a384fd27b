#!/usr/bin/python3
"""The plots of a `dynslam compare` directory: DIR/convergence.png (every formulation's
convergence.csv, the paper's Fig. 4), DIR/trajectory.png (every formulation's cameras and object
poses, top view, with the ground truth) and, with --gt, DIR/errors.png (errors per frame).
`dynslam compare` runs it after its tables; a plot that cannot be drawn is one warning line and
the others are still drawn (exit 1 when any was not).

    scripts/plot_compare.py cmp --labels wc oc_b --gt scene.gt.txt --title scene.g2o
"""
import argparse
import os
import sys

PLOTS = "convergence.png, trajectory.png and errors.png"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", help="the compare's output directory (DIR/<label>/ per formulation)")
    parser.add_argument("--labels", nargs="+", required=True, help="the formulations' folders")
    parser.add_argument("--gt", help="ground-truth file (SPEC §2)")
    parser.add_argument("--title", default="", help="what the titles start with")
    args = parser.parse_args()
    try:
        import plot_convergence
        import plot_errors
        import plot_trajectory
    except ImportError as error:
        sys.exit(f"warning: {sys.executable} cannot import {error.name} (Debian: "
                 f"python3-matplotlib), so no {PLOTS}")
    folders = [os.path.join(args.dir, label) for label in args.labels]
    plots = [("convergence.png", lambda out: plot_convergence.draw(
                  [os.path.join(f, "convergence.csv") for f in folders], args.labels,
                  f"{args.title}: convergence (Fig. 4)", out)),
             ("trajectory.png", lambda out: plot_trajectory.draw(
                  folders, args.labels, args.gt, f"{args.title}: trajectories (top view, x-z)",
                  out))]
    if args.gt:
        plots.append(("errors.png", lambda out: plot_errors.draw(
            [os.path.join(f, "errors.csv") for f in folders], args.labels,
            f"{args.title}: errors per frame", out)))
    failed = 0
    for image, draw in plots:
        out = os.path.join(args.dir, image)
        try:
            draw(out)
            print(f"[compare] wrote {out}")
        except (SystemExit, Exception) as error:  # the scripts exit with FILE:LINE: problem
            failed += 1
            print(f"warning: no {image}: {error}", file=sys.stderr)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
