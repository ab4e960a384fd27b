#!/usr/bin/python3
"""Top-down trajectories from one or more solve output directories (SPEC §4).

Plots the x–z plane of the world frame (KITTI's camera y points down, so this is the view from
above, x to the right, z forward): the camera path from cameras.csv and each object's path (the
translations of object_poses.csv), estimates as solid lines, the ground truth (--gt, SPEC §2) as
dashed lines, one colour per object. With several directories each estimate has its own marker.
A path is broken where frames are missing (an object out of view, a dropped segment).

    scripts/plot_trajectory.py out/wc out/oc_b --labels wc oc_b \
        --gt data/reference/synthetic/gt.txt --out trajectory.png

A malformed file is reported as FILE:LINE: problem, with exit code 1.
"""
import argparse
import math
import os
import sys

CAMERA_COLUMNS = ["frame", "tx", "ty", "tz", "qx", "qy", "qz", "qw"]
OBJECT_COLUMNS = ["object", "frame", "tx", "ty", "tz", "qx", "qy", "qz", "qw"]
RUN_MARKERS = ["o", "s", "^", "v", "D", "P", "X", "*"]


def fail(path, line, message):
    sys.exit(f"{path}:{line}: {message}" if line else f"{path}: {message}")


def parse_index(text, what, path, line):
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        fail(path, line, f"{what} '{text}' is not a non-negative integer")
    return value


def parse_number(text, path, line):
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        fail(path, line, f"field '{text}' is not a finite number")
    return value


def read_lines(path):
    """The file's lines; an unreadable file is an error, not a traceback."""
    try:
        with open(path, encoding="utf-8") as f:
            return f.read().splitlines()
    except OSError as error:
        fail(path, 0, f"cannot read the file: {error.strerror or error}")
    except UnicodeDecodeError as error:
        fail(path, 0, f"not a text file (byte {error.object[error.start]:#04x} "
                      f"at offset {error.start})")


def read_csv(path, columns):
    """{key: (x, z)} from a cameras.csv (key = frame) or object_poses.csv (key = (object, frame)).

    The files are written by dynslam without quoting (src/solve_output.cc), so a record is its
    line split at commas; blank lines are skipped.
    """
    lines = read_lines(path)
    if not lines:
        fail(path, 1, "empty file, expected the header " + ",".join(columns))
    if [name.strip() for name in lines[0].split(",")] != columns:
        fail(path, 1, f"header '{lines[0]}' is not " + ",".join(columns))
    n_index = len(columns) - 7  # frame, or object and frame, before tx ty tz qx qy qz qw
    rows = {}
    for line, text in enumerate(lines[1:], start=2):
        if not text.strip():
            continue
        fields = [field.strip() for field in text.split(",")]
        if len(fields) != len(columns):
            fail(path, line, f"{len(fields)} fields, expected {len(columns)} "
                             f"({','.join(columns)})")
        index = tuple(parse_index(fields[i], columns[i], path, line) for i in range(n_index))
        pose = [parse_number(field, path, line) for field in fields[n_index:]]
        key = index[0] if n_index == 1 else index
        if key in rows:
            fail(path, line, "second row for " + ", ".join(
                f"{name} {value}" for name, value in zip(columns, index)))
        rows[key] = (pose[0], pose[2])
    return rows


def read_solve_dir(directory):
    for name in ("cameras.csv", "object_poses.csv"):
        if not os.path.isfile(os.path.join(directory, name)):
            fail(directory, 0, f"not a solve output directory (no {name}, SPEC §4)")
    cameras = read_csv(os.path.join(directory, "cameras.csv"), CAMERA_COLUMNS)
    objects = read_csv(os.path.join(directory, "object_poses.csv"), OBJECT_COLUMNS)
    return cameras, objects


def read_ground_truth(path):
    """CAMERA k tx ty tz qx qy qz qw / OBJECT k j tx ty tz qx qy qz qw (SPEC §2)."""
    cameras, objects = {}, {}
    for line, text in enumerate(read_lines(path), start=1):
        fields = text.split("#", 1)[0].split()
        if not fields:
            continue
        camera = fields[0] == "CAMERA"
        if not camera and fields[0] != "OBJECT":
            fail(path, line, f"unknown record '{fields[0]}' (CAMERA or OBJECT, SPEC §2)")
        expected = 9 if camera else 10
        if len(fields) != expected:
            fail(path, line, f"{fields[0]} has {len(fields) - 1} fields, expected {expected - 1}"
                             + (" (k tx ty tz qx qy qz qw)" if camera
                                else " (k j tx ty tz qx qy qz qw)"))
        frame = parse_index(fields[1], "frame", path, line)
        first = 2 if camera else 3
        pose = [parse_number(field, path, line) for field in fields[first:]]
        if all(q == 0 for q in pose[3:]):
            fail(path, line, "zero quaternion")
        if camera:
            key, table, what = frame, cameras, f"CAMERA record for frame {frame}"
        else:
            obj = parse_index(fields[2], "object", path, line)
            key, table = (obj, frame), objects
            what = f"OBJECT record for object {obj} at frame {frame}"
        if key in table:
            fail(path, line, "second " + what)
        table[key] = (pose[0], pose[2])
    return cameras, objects


def path_xz(frames_to_xz):
    """x and z lists in frame order, with a break (nan) wherever a frame is missing."""
    xs, zs, previous = [], [], None
    for frame in sorted(frames_to_xz):
        if previous is not None and frame != previous + 1:
            xs.append(math.nan)
            zs.append(math.nan)
        x, z = frames_to_xz[frame]
        xs.append(x)
        zs.append(z)
        previous = frame
    return xs, zs


def by_object(objects):
    paths = {}
    for (obj, frame), xz in objects.items():
        paths.setdefault(obj, {})[frame] = xz
    return paths


def draw(dirs, labels, gt_path, title, out):
    """The top view of the solve output directories `dirs` (and the ground truth at `gt_path`,
    when given) into `out`."""
    # Read everything before plotting so that bad input stops the script before any drawing.
    runs = [(label, *read_solve_dir(directory)) for directory, label in zip(dirs, labels)]
    gt = read_ground_truth(gt_path) if gt_path else None

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.lines import Line2D
    except ImportError as error:
        sys.exit(f"cannot import matplotlib ({error}); install python3-matplotlib")

    object_ids = set()
    for _, _, objects in runs + ([("gt", *gt)] if gt else []):
        object_ids.update(obj for obj, _ in objects)
    palette = plt.get_cmap("tab10").colors
    colours = {obj: palette[i % len(palette)] for i, obj in enumerate(sorted(object_ids))}

    fig, ax = plt.subplots(figsize=(8, 8))
    several = len(runs) > 1

    def draw(cameras, objects, style, marker):
        options = {"linestyle": style, "linewidth": 1.2 if style == "-" else 1.0}
        if marker:
            options.update(marker=marker, markersize=4, markevery=5, fillstyle="none")
        if cameras:
            ax.plot(*path_xz(cameras), color="black", **options)
        for obj, frames in sorted(by_object(objects).items()):
            ax.plot(*path_xz(frames), color=colours[obj], **options)

    if gt:
        draw(*gt, "--", None)
    for i, (_, cameras, objects) in enumerate(runs):
        draw(cameras, objects, "-", RUN_MARKERS[i % len(RUN_MARKERS)] if several else None)

    # Legend: colours name the paths, line styles (and markers) name the sources.
    handles = [Line2D([], [], color="black", label="camera")]
    handles += [Line2D([], [], color=colours[obj], label=f"object {obj}")
                for obj in sorted(object_ids)]
    for i, (label, _, _) in enumerate(runs):
        handles.append(Line2D([], [], color="grey", linestyle="-",
                              marker=RUN_MARKERS[i % len(RUN_MARKERS)] if several else None,
                              fillstyle="none", label=f"estimate: {label}" if several
                              else f"estimate ({label})"))
    if gt:
        handles.append(Line2D([], [], color="grey", linestyle="--", label="ground truth"))
    ax.legend(handles=handles, loc="best", fontsize="small")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m), forward")
    ax.set_title(title)
    ax.grid(True, linewidth=0.4, alpha=0.5)
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=120)
    except (OSError, ValueError) as error:
        fail(out, 0, f"cannot write the image ({error})")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dirs", nargs="+", help="solve output directories (dynslam solve --out)")
    parser.add_argument("--labels", nargs="*", help="one label per directory (default: the paths)")
    parser.add_argument("--gt", help="ground-truth file (SPEC §2), drawn dashed")
    parser.add_argument("--title", default="Trajectories (top view, x–z)")
    parser.add_argument("--out", required=True, help="image file (.png, .pdf, .svg)")
    args = parser.parse_args()
    labels = args.labels or args.dirs
    if len(labels) != len(args.dirs):
        sys.exit("--labels needs one label per directory")
    draw(args.dirs, labels, args.gt, args.title, args.out)
    print(args.out)


if __name__ == "__main__":
    main()
