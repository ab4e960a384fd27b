#!/usr/bin/python3
"""Per-frame errors of one or more solves (their errors.csv, SPEC §4): the camera's relative pose
error, and each frame's object motion and object pose errors averaged over the objects there,
E_r (deg) and E_t (m), one line per solve. `dynslam compare --gt` draws it as errors.png.

    scripts/plot_errors.py out/wc/errors.csv out/oc_b/errors.csv --labels wc oc_b --out errors.png
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

QUANTITIES = [("camera", "camera"), ("object_motion", "object motion, mean over objects"),
              ("object_pose", "object pose, mean over objects")]


def read_means(path):
    """{quantity: {frame: (mean rot_deg, mean trans_m)}} from an errors.csv."""
    sums = defaultdict(lambda: defaultdict(lambda: [0.0, 0.0, 0]))
    try:
        f = open(path, newline="")
    except OSError as error:
        sys.exit(f"{path}: cannot read the file: {error.strerror or error}")
    with f:
        reader = csv.DictReader(f)
        if reader.fieldnames != ["quantity", "object", "frame", "rot_deg", "trans_m"]:
            sys.exit(f"{path}: not an errors.csv (quantity,object,frame,rot_deg,trans_m)")
        for line, row in enumerate(reader, start=2):
            try:
                total = sums[row["quantity"]][int(row["frame"])]
                total[0] += float(row["rot_deg"])
                total[1] += float(row["trans_m"])
                total[2] += 1
            except ValueError as error:
                sys.exit(f"{path}:{line}: {error}")
    return {q: {k: (r / n, t / n) for k, (r, t, n) in frames.items()} for q, frames in sums.items()}


def draw(paths, labels, title, out):
    """The figure of the errors.csv files `paths`, one line per label, into `out`."""
    fig, axes = plt.subplots(len(QUANTITIES), 2, sharex=True, figsize=(10, 8), squeeze=False)
    for path, label in zip(paths, labels):
        means = read_means(path)
        for row, (quantity, _) in enumerate(QUANTITIES):
            frames = sorted(means.get(quantity, {}))
            for column in (0, 1):
                axes[row][column].plot(frames, [means[quantity][k][column] for k in frames],
                                       ".-", markersize=3, label=label)
    for row, (_, title) in enumerate(QUANTITIES):
        axes[row][0].set_ylabel(f"{title}\nE_r (deg)")
        axes[row][1].set_ylabel("E_t (m)")
    for column in (0, 1):
        axes[-1][column].set_xlabel("frame")
    axes[0][0].legend()
    fig.suptitle(title)
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=120)
    except (OSError, ValueError) as error:
        sys.exit(f"{out}: cannot write the image ({error})")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="errors.csv files")
    parser.add_argument("--labels", nargs="*", help="one label per file (default: the paths)")
    parser.add_argument("--title", default="Errors per frame")
    parser.add_argument("--out", required=True, help="image file (.png, .pdf, .svg)")
    args = parser.parse_args()
    labels = args.labels or args.csv
    if len(labels) != len(args.csv):
        sys.exit("--labels needs one label per file")
    draw(args.csv, labels, args.title, args.out)
    print(args.out)


if __name__ == "__main__":
    main()
