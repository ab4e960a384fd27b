#!/usr/bin/python3
"""The paper's Tables I–III (Morris, Wang, Ila, ICRA 2024) next to ours, from the tables.csv of
one `dynslam compare` per KITTI sequence (scripts/demo writes them as OUT/kitti_NNNN/tables.csv),
and the scene statistics of each simulated sequence (OUT/kitti_NNNN/simulate.txt, the output of
`dynslam simulate`).

    scripts/paper_tables.py OUT [--out OUT/paper_tables.md]

The paper's numbers below are typed from its LaTeX source (Morris, Wang, Ila, ICRA 2024): they are the
published values, not outputs of this code. Columns: object-centric (oc_a), with OKF (oc_b),
only OKF (oc_c), world-centric (wc). The paper's Table I has no oc_c column.
"""
import argparse
import collections
import csv
import pathlib
import sys

# Table I: sequence → camera (E_r deg, E_t m) for oc_a, oc_b, wc; # variables oc, wc; time oc, wc.
PAPER_CAMERA = {
    "0000": ((0.06, 0.05), (0.09, 0.05), (0.05, 0.04), 26335, 153155, 365.3, 72.0),
    "0001": ((0.05, 0.04), (0.07, 0.04), (0.04, 0.03), 51426, 117923, 38.4, 34.2),
    "0002": ((0.02, 0.03), (0.06, 0.03), (0.02, 0.03), 19034, 38450, 102.0, 22.4),
    "0003": ((0.05, 0.07), (0.09, 0.07), (0.03, 0.06), 20410, 92264, 215.4, 24.8),
    "0004": ((0.04, 0.07), (0.06, 0.06), (0.04, 0.06), 36486, 80352, 39.8, 22.3),
    "0005": ((0.03, 0.06), (0.07, 0.06), (0.02, 0.06), 31369, 99990, 63.9, 41.8),
    "0006": ((0.06, 0.02), (0.07, 0.02), (0.05, 0.01), 21353, 91187, 225.7, 73.9),
    "0018": ((0.03, 0.04), (0.1, 0.04), (0.02, 0.04), 53680, 340844, 269.2, 381.5),
    "0020": ((0.03, 0.05), (0.1, 0.05), (0.03, 0.05), 129316, 711804, 422.6, 656.9),
}
# Tables II (motion) and III (pose): (sequence, object) → ((E_r, E_t) for oc_a, oc_b, oc_c, wc);
# object "mean" is the mean over all objects of the sequence.
PAPER_MOTION = {
    ("0000", "1"): ((3.54, 1.7), (1.27, 0.49), (1.01, 0.4), (0.9, 0.51)),
    ("0000", "mean"): ((4.73, 3.85), (1.67, 1.35), (1.05, 1.11), (0.78, 0.52)),
    ("0003", "1"): ((2.14, 1.07), (3.87, 1.26), (0.68, 0.4), (0.22, 0.17)),
    ("0003", "mean"): ((0.93, 5.39), (2.38, 1.12), (0.46, 0.34), (0.24, 0.23)),
    ("0004", "3"): ((5.22, 2.47), (2.7, 1.08), (1.82, 0.73), (0.64, 0.37)),
    ("0004", "4"): ((1.13, 4.63), (1.9, 0.85), (1.19, 0.59), (0.38, 0.23)),
    ("0004", "5"): ((3.57, 6.55), (2.56, 1.21), (1.13, 0.62), (0.5, 0.33)),
    ("0004", "mean"): ((5.48, 5.08), (2.13, 2.11), (1.81, 1.35), (0.77, 0.51)),
    ("0005", "20"): ((1.91, 6.54), (4.79, 30.77), (1.94, 5.38), (0.53, 1.37)),
    ("0005", "24"): ((4.74, 18.28), (1.19, 5.48), (3.45, 15.04), (0.51, 2.28)),
    ("0005", "mean"): ((1.66, 13.68), (0.18, 12.43), (2.01, 7.73), (0.7, 5.19)),
    ("0018", "4"): ((6.1, 14.50), (1.83, 4.68), (0.89, 4.07), (0.25, 1.82)),
    ("0018", "mean"): ((0.25, 11.26), (0.97, 25.67), (1.17, 4.67), (0.52, 1.95)),
    ("0020", "32"): ((3.60, 2.17), (0.42, 0.23), (0.32, 0.17), (0.08, 0.15)),
    ("0020", "mean"): ((4.90, 14.70), (1.15, 5.96), (1.21, 7.17), (0.69, 5.46)),
}
PAPER_POSE = {
    ("0000", "1"): ((3.63, 0.38), (1.33, 0.26), (1.07, 0.35), (0.92, 0.22)),
    ("0000", "mean"): ((3.72, 0.38), (1.51, 0.36), (1.11, 0.33), (0.79, 0.15)),
    ("0003", "1"): ((3.79, 0.68), (3.85, 1.94), (0.67, 0.83), (0.2, 0.15)),
    ("0003", "mean"): ((3.73, 0.72), (2.37, 1.4), (0.46, 0.46), (0.24, 0.15)),
    ("0004", "3"): ((3.28, 0.9), (2.63, 1.18), (1.79, 1.11), (0.64, 0.12)),
    ("0004", "4"): ((4.13, 0.88), (2.1, 0.89), (1.39, 0.97), (0.38, 0.12)),
    ("0004", "5"): ((0.51, 1.11), (2.58, 1.03), (1.09, 1.09), (0.43, 0.15)),
    ("0004", "mean"): ((3.74, 0.9), (2.23, 0.87), (1.92, 0.93), (0.76, 0.1)),
    ("0005", "20"): ((2.64, 3.02), (4.58, 2.73), (2.05, 3.19), (0.54, 0.23)),
    ("0005", "24"): ((5.29, 2.74), (1.34, 2.79), (3.37, 3.1), (0.53, 0.15)),
    ("0005", "mean"): ((2.25, 2.05), (0.29, 1.94), (2.07, 2.33), (0.63, 0.55)),
    ("0018", "4"): ((0.78, 0.20), (1.92, 0.09), (0.94, 0.16), (0.26, 0.19)),
    ("0018", "mean"): ((1.69, 1.34), (1.08, 1.00), (1.21, 1.48), (0.53, 0.27)),
    ("0020", "32"): ((0.77, 0.21), (0.45, 0.08), (0.35, 0.12), (0.08, 0.03)),
    ("0020", "mean"): ((1.90, 0.31), (1.28, 0.20), (1.33, 0.58), (0.68, 0.53)),
}
FORMULATIONS = ("oc_a", "oc_b", "oc_c", "wc")


def read_tables(path):
    """tables.csv → {(table, formulation, object, quantity): value}; numbers as floats, the one
    text quantity (termination) as text."""
    values = {}
    with open(path, newline="") as f:
        for line, row in enumerate(csv.DictReader(f), start=2):
            try:
                key = (row["table"], row["formulation"], row["object"] or "", row["quantity"])
                text = row["value"]
                values[key] = text if row["quantity"] == "termination" else float(text)
            except (KeyError, TypeError, ValueError):
                sys.exit(f"{path}:{line}: not a row of dynslam compare's tables.csv")
    return values


SCENE_FIELDS = ("frames", "static_points", "moving_objects", "dynamic_observations", "motions")


def read_scene(path):
    """The scene block of `dynslam simulate`'s output: {name: first value} for SCENE_FIELDS."""
    scene = {}
    if path.exists():
        for line in path.read_text().splitlines():
            fields = line.split()
            if len(fields) >= 2 and fields[0] in SCENE_FIELDS:
                scene[fields[0]] = fields[1]
    return scene


def digits(x):
    """Two decimals, as the paper prints them, or two significant digits where that would show
    0.00 (our simulated camera errors are millimetres)."""
    return f"{x:.2f}" if abs(x) >= 0.005 or x == 0 else f"{x:.2g}"


def pair(values, table, formulation, obj, rot, trans):
    r = values.get((table, formulation, obj, rot))
    t = values.get((table, formulation, obj, trans))
    return "– / –" if r is None or t is None else f"{digits(r)} / {digits(t)}"


def paper_pair(p):
    return f"{p[0]:.2f} / {p[1]:.2f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root", help="folder with kitti_NNNN/tables.csv from dynslam compare")
    parser.add_argument("--out", help="Markdown file (default ROOT/paper_tables.md)")
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    results = {}
    scenes = {}
    for tables in sorted(root.glob("kitti_*/tables.csv")):
        seq = tables.parent.name.split("_", 1)[1]
        results[seq] = read_tables(tables)
        scenes[seq] = read_scene(tables.parent / "simulate.txt")
    if not results:
        sys.exit(f"{root}: no kitti_NNNN/tables.csv (run scripts/demo first)")

    md = ["### Table I: camera RPE, E_r (deg) / E_t (m) — ours | paper", "",
          "| seq | oc_a | paper oc | oc_b | paper OKF | oc_c | wc | paper wc | variables oc / wc | "
          "paper | solve s oc_b / wc | paper oc / wc |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for seq, v in results.items():
        p = PAPER_CAMERA.get(seq)
        cam = {f: pair(v, "I", f, "", "camera_rot_deg", "camera_trans_m") for f in FORMULATIONS}
        var = {f: v.get(("I", f, "", "variables")) for f in FORMULATIONS}
        time = {f: v.get(("I", f, "", "solve_time_s")) for f in FORMULATIONS}
        md.append(
            f"| {seq} | {cam['oc_a']} | {paper_pair(p[0]) if p else '–'} | {cam['oc_b']} | "
            f"{paper_pair(p[1]) if p else '–'} | {cam['oc_c']} | {cam['wc']} | "
            f"{paper_pair(p[2]) if p else '–'} | {var['oc_b']:.0f} / {var['wc']:.0f} | "
            f"{f'{p[3]} / {p[4]}' if p else '–'} | {digits(time['oc_b'])} / {digits(time['wc'])} | "
            f"{f'{p[5]} / {p[6]}' if p else '–'} |")

    for table, title, paper in (("II", "object motion", PAPER_MOTION),
                                ("III", "object pose", PAPER_POSE)):
        md += ["", f"### Table {table}: {title} error, E_r (deg) / E_t (m) — ours (paper)", "",
               "| seq / object | oc_a | oc_b (OKF) | oc_c (only OKF) | wc |", "|---|---|---|---|---|"]
        for (seq, obj), p in paper.items():
            if seq not in results:
                continue
            cells = []
            for i, f in enumerate(FORMULATIONS):
                cells.append(f"{pair(results[seq], table, f, obj, 'rot_deg', 'trans_m')} "
                             f"({paper_pair(p[i])})")
            md.append(f"| {seq} / {obj} | " + " | ".join(cells) + " |")
    md += ["", "### Scene statistics (simulated front end) and variables per formulation", "",
           "| seq | " + " | ".join(f.replace("_", " ") for f in SCENE_FIELDS) + " | " +
           " | ".join(f"variables {f}" for f in FORMULATIONS) + " |",
           "|---" * (1 + len(SCENE_FIELDS) + len(FORMULATIONS)) + "|"]
    for seq, v in results.items():
        counts = [f"{v[('I', f, '', 'variables')]:.0f}" if ("I", f, "", "variables") in v else "–"
                  for f in FORMULATIONS]
        md.append(f"| {seq} | " + " | ".join(scenes[seq].get(f, "–") for f in SCENE_FIELDS) +
                  " | " + " | ".join(counts) + " |")
    text = "\n".join(md) + "\n"
    out = pathlib.Path(args.out) if args.out else root / "paper_tables.md"
    out.write_text(text)
    print(text)


if __name__ == "__main__":
    main()
