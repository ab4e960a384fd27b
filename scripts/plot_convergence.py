#!/usr/bin/python3
"""The paper's Fig. 4 from one or more convergence.csv files (SPEC §4).

Top: cost (χ²/2) per linear solve on a log scale, accepted steps as dots, rejected steps as
crosses at their trial cost; a relinearisation (every accepted step) is a vertical tick.
Middle: the cost change of each step (cost − trial cost; negative for rejected steps), symlog.
Bottom: the cost against the time since the minimiser started (time_s), the same curves in seconds.

    scripts/plot_convergence.py out/wc/convergence.csv out/oc_b/convergence.csv \
        --labels wc oc_b --out fig4.png
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    try:
        f = open(path, newline="")
    except OSError as error:
        sys.exit(f"{path}: cannot read the file: {error.strerror or error}")
    with f:
        rows = list(csv.DictReader(f))
    needed = {"step", "iteration", "lambda", "cost", "trial_cost", "accepted", "time_s"}
    if rows and not needed.issubset(rows[0].keys()):
        sys.exit(f"{path}: not a convergence.csv (columns {sorted(needed)})")
    out = []
    for line, row in enumerate(rows, start=2):
        try:
            out.append({
                "step": int(row["step"]),
                "cost": float(row["cost"]),
                "trial": float(row["trial_cost"]),
                "accepted": row["accepted"].strip() == "1",
                "time": float(row["time_s"]),
            })
        except ValueError as error:
            sys.exit(f"{path}:{line}: {error}")
    return out


def draw(paths, labels, title, out):
    """The figure of the convergence.csv files `paths`, one curve per label, into `out`."""
    fig = plt.figure(figsize=(8, 9))
    top = fig.add_subplot(3, 1, 1)
    bottom = fig.add_subplot(3, 1, 2, sharex=top)
    timed = fig.add_subplot(3, 1, 3)
    for path, label in zip(paths, labels):
        rows = read_rows(path)
        if not rows:
            continue
        # The cost after each step, from the initial cost at step 0 (time 0).
        after = [rows[0]["cost"]] + [r["trial"] if r["accepted"] else r["cost"] for r in rows]
        line, = top.plot([0] + [r["step"] for r in rows], after, "-", label=label)
        timed.plot([0.0] + [r["time"] for r in rows], after, ".-", color=line.get_color(),
                   markersize=3, label=label)
        color = line.get_color()
        accepted = [r for r in rows if r["accepted"]]
        rejected = [r for r in rows if not r["accepted"] and math.isfinite(r["trial"])]
        top.plot([r["step"] for r in accepted], [r["trial"] for r in accepted], "o",
                 color=color, markersize=3)
        top.plot([r["step"] for r in rejected], [r["trial"] for r in rejected], "x",
                 color=color, markersize=5)
        for r in accepted:
            top.axvline(r["step"], color=color, alpha=0.12, linewidth=0.8)
        bottom.plot([r["step"] for r in rows],
                    [r["cost"] - r["trial"] if math.isfinite(r["trial"]) else 0.0 for r in rows],
                    ".-", color=color, label=label)
    top.set_yscale("log")
    top.set_ylabel("cost ½χ² (o accepted, x rejected trial)")
    top.set_title(title)
    top.legend()
    bottom.set_yscale("symlog", linthresh=1e-6)
    bottom.set_ylabel("cost change per step")
    bottom.set_xlabel("linear solve (step); faint lines: relinearisations")
    timed.set_yscale("log")
    timed.set_ylabel("cost ½χ²")
    timed.set_xlabel("time since the minimiser started (s)")
    bottom.axhline(0, color="black", linewidth=0.5)
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=120)
    except (OSError, ValueError) as error:
        sys.exit(f"{out}: cannot write the image ({error})")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="convergence.csv files")
    parser.add_argument("--labels", nargs="*", help="one label per file (default: the paths)")
    parser.add_argument("--title", default="Convergence (Fig. 4)")
    parser.add_argument("--out", required=True, help="image file (.png, .pdf, .svg)")
    args = parser.parse_args()
    labels = args.labels or args.csv
    if len(labels) != len(args.csv):
        sys.exit("--labels needs one label per file")
    draw(args.csv, labels, args.title, args.out)
    print(args.out)


if __name__ == "__main__":
    main()
