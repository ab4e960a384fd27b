#!/usr/bin/python3
"""Error against ±3σ per frame (docs/COVARIANCE.md): for the camera, and for one object's poses
(object-centric graphs) or motions (world-centric), each tangent component of the error
δ = Log(X⁻¹·X_gt) (SPEC §1.3: [ω; ρ], rad and m) with the band ±3·sqrt(Σ_ii) of the variable's
marginal covariance. Reads a `dynslam solve … --covariance …` output directory.

    scripts/plot_uncertainty.py DIR --gt GT.txt [--object J] [--out DIR/uncertainty.png]
"""
import argparse
import csv
import os
import sys

import numpy as np

COMPONENTS = ["ω_x (rad)", "ω_y (rad)", "ω_z (rad)", "ρ_x (m)", "ρ_y (m)", "ρ_z (m)"]


def pose_matrix(values):
    """[tx ty tz qx qy qz qw] → 4×4 (SPEC §0's file order)."""
    t, (x, y, z, w) = np.array(values[:3]), values[3:]
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = r, t
    return m


def log_se3(m):
    """Log of a 4×4 pose as [ω; ρ] (t = V(ω)·ρ)."""
    r, t = m[:3, :3], m[:3, 3]
    cos = np.clip((np.trace(r) - 1) / 2, -1.0, 1.0)
    theta = np.arccos(cos)
    skew = (r - r.T) / 2
    omega_hat = skew if theta < 1e-9 else skew * theta / np.sin(theta)
    omega = np.array([omega_hat[2, 1], omega_hat[0, 2], omega_hat[1, 0]])
    if theta < 1e-9:
        v_inv = np.eye(3) - omega_hat / 2
    else:
        v_inv = (np.eye(3) - omega_hat / 2 + (1 - theta * np.sin(theta) / (2 * (1 - np.cos(theta))))
                 / theta ** 2 * omega_hat @ omega_hat)
    return np.concatenate([omega, v_inv @ t])


def read_solution(path):
    """id → (4×4 pose or None for points, (role, object, frame)) from solution.g2o."""
    poses, labels = {}, {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if fields and fields[0] == "VERTEX_SE3:QUAT":
                poses[int(fields[1])] = pose_matrix([float(v) for v in fields[2:9]])
            elif fields and fields[0] in ("LABEL_CAMERA", "LABEL_MOTION", "LABEL_OBJECT_POSE"):
                numbers = [int(v) for v in fields[2:]]
                obj, frame = (-1, numbers[0]) if fields[0] == "LABEL_CAMERA" else numbers[:2]
                labels[int(fields[1])] = (fields[0][6:].lower(), obj, frame)
    return poses, labels


def read_covariances(path):
    """id → the 6×6 covariance of each pose row of covariances.csv."""
    out = {}
    with open(path, newline="") as f:
        for row in csv.reader(f):
            if row[0] == "id" or row[2] != "6":
                continue
            upper, m, k = [float(v) for v in row[3:]], np.zeros((6, 6)), 0
            for r in range(6):
                for c in range(r, 6):
                    m[r, c] = m[c, r] = upper[k]
                    k += 1
            out[int(row[0])] = m
    return out


def read_ground_truth(path):
    """('camera', -1, frame) and ('object', j, frame) → 4×4 (SPEC §2)."""
    truth = {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            if fields[0] == "CAMERA":
                truth[("camera", -1, int(fields[1]))] = pose_matrix([float(v) for v in fields[2:9]])
            elif fields[0] == "OBJECT":  # OBJECT k j …: frame, then object
                truth[("object", int(fields[2]), int(fields[1]))] = pose_matrix(
                    [float(v) for v in fields[3:10]])
    return truth


def series(poses, labels, covariances, truth, role, obj):
    """Frames, errors (n×6) and σ (n×6) of one role (and object) with covariance and truth."""
    rows = []
    for vid, (r, o, frame) in labels.items():
        if r != role or o != obj or vid not in covariances:
            continue
        if role == "motion":
            now, before = truth.get(("object", obj, frame)), truth.get(("object", obj, frame - 1))
            gt = None if now is None or before is None else now @ np.linalg.inv(before)
        else:
            gt = truth.get(("camera" if role == "camera" else "object", obj, frame))
        if gt is not None:
            error = log_se3(np.linalg.inv(poses[vid]) @ gt)
            rows.append((frame, error, np.sqrt(np.diag(covariances[vid]))))
    rows.sort(key=lambda r: r[0])
    return (np.array([r[0] for r in rows]), np.array([r[1] for r in rows]),
            np.array([r[2] for r in rows]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", help="a dynslam solve output directory with covariances.csv")
    parser.add_argument("--gt", required=True, help="the ground-truth file (SPEC §2)")
    parser.add_argument("--object", type=int, help="also this object's poses or motions")
    parser.add_argument("--out", help="PNG to write (default DIR/uncertainty.png)")
    args = parser.parse_args()
    for name in ("solution.g2o", "covariances.csv"):
        if not os.path.isfile(os.path.join(args.dir, name)):
            sys.exit(f"error: {args.dir}: no {name} (run dynslam solve … --covariance first)")
    poses, labels = read_solution(os.path.join(args.dir, "solution.g2o"))
    covariances = read_covariances(os.path.join(args.dir, "covariances.csv"))
    truth = read_ground_truth(args.gt)
    panels = [("camera", -1)]
    if args.object is not None:
        roles = {r for r, o, _ in labels.values() if o == args.object}
        panels.append(("object_pose" if "object_pose" in roles else "motion", args.object))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(6, len(panels), figsize=(5 * len(panels), 10), squeeze=False,
                                sharex="col")
    for column, (role, obj) in enumerate(panels):
        frames, errors, sigmas = series(poses, labels, covariances, truth, role, obj)
        if len(frames) == 0:
            sys.exit(f"error: no {role} of {args.dir} has both a covariance and ground truth")
        title = "camera" if role == "camera" else f"object {obj} {role.replace('_', ' ')}"
        axes[0, column].set_title(f"{title}: error and ±3σ")
        for k in range(6):
            ax = axes[k, column]
            ax.fill_between(frames, -3 * sigmas[:, k], 3 * sigmas[:, k], color="C0", alpha=0.25)
            ax.plot(frames, errors[:, k], color="C3", lw=1)
            ax.set_ylabel(COMPONENTS[k])
        axes[5, column].set_xlabel("frame")
    figure.tight_layout()
    out = args.out or os.path.join(args.dir, "uncertainty.png")
    figure.savefig(out, dpi=100)
    print(out)


if __name__ == "__main__":
    main()
