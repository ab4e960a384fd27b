#!/usr/bin/env python3
"""`dynslam solve --export tum,kitti`: the trajectory files alone give back SPEC §5's camera
relative pose error, and (object-centric) the object pose error, of summary.json to 1e-9.
The pose algebra here is written from SPEC §0/§5 with plain Python, not the project's code.

Usage: trajectory_export_test.py DYNSLAM_BINARY REPOSITORY_ROOT
"""
import json
import math
import os
import subprocess
import sys
import tempfile

DYNSLAM, ROOT = sys.argv[1], sys.argv[2]
RATE_HZ = 10.0
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def quaternion_to_matrix(qx, qy, qz, qw):
    n = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    x, y, z, w = qx / n, qy / n, qz / n, qw / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def compose(a, b):  # (R, t) pairs: a · b
    ra, ta = a
    rb, tb = b
    r = [[sum(ra[i][k] * rb[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    t = [sum(ra[i][k] * tb[k] for k in range(3)) + ta[i] for i in range(3)]
    return r, t


def inverse(a):
    r, t = a
    rt = [[r[j][i] for j in range(3)] for i in range(3)]
    return rt, [-sum(rt[i][k] * t[k] for k in range(3)) for i in range(3)]


def pose_error(estimate, truth):
    """SPEC §5: E = M⁻¹ · M_gt; (angle of R(E) in degrees, ‖t(E)‖)."""
    r, t = compose(inverse(estimate), truth)
    cosine = max(-1.0, min(1.0, (r[0][0] + r[1][1] + r[2][2] - 1) / 2))
    return math.degrees(math.acos(cosine)), math.sqrt(sum(v * v for v in t))


def read_tum(path):
    poses = {}
    with open(path) as f:
        for line in f:
            t, x, y, z, qx, qy, qz, qw = map(float, line.split())
            poses[round(t * RATE_HZ)] = (quaternion_to_matrix(qx, qy, qz, qw), [x, y, z])
    return poses


def read_kitti(path, frames):
    """KITTI lines carry no time: the frames are those of the TUM file of the same trajectory."""
    poses = {}
    with open(path) as f:
        lines = f.read().split("\n")[:-1]
    check(len(lines) == len(frames), f"{path}: {len(lines)} lines for {len(frames)} frames")
    for frame, line in zip(sorted(frames), lines):
        v = list(map(float, line.split()))
        poses[frame] = ([v[0:3], v[4:7], v[8:11]], [v[3], v[7], v[11]])
    return poses


def mean_relative_error(estimate, truth, frames=None):
    """Mean E_r, E_t of L_{k−1}⁻¹·L_k over consecutive frames both have (and in `frames`)."""
    errors = []
    for k in sorted(estimate):
        if frames is not None and k not in frames:
            continue
        if k - 1 in estimate and k in truth and k - 1 in truth:
            errors.append(pose_error(compose(inverse(estimate[k - 1]), estimate[k]),
                                     compose(inverse(truth[k - 1]), truth[k])))
    if not errors:
        return 0.0, 0.0, 0
    return (sum(e[0] for e in errors) / len(errors), sum(e[1] for e in errors) / len(errors),
            len(errors))


def close(ours, expected):
    return abs(ours - expected) <= 1e-9 * max(1.0, abs(expected))


def check_scene(formulation, work):
    scene = os.path.join(ROOT, "data", "reference", "synthetic")
    out = os.path.join(work, formulation)
    result = subprocess.run([DYNSLAM, "solve", os.path.join(scene, "graphs", formulation + ".g2o"),
                             "--gt", os.path.join(scene, "gt.txt"), "--out", out,
                             "--export", "tum,kitti"], capture_output=True, text=True)
    check(result.returncode == 0, f"{formulation}: solve exit {result.returncode}: {result.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        metrics = json.load(f)["metrics"]
    names = sorted(n for n in os.listdir(out) if n.endswith(".tum.txt"))
    check("camera_estimate.tum.txt" in names and "camera_ground_truth.tum.txt" in names,
          f"{formulation}: camera files written ({names})")
    for fmt in ("tum", "kitti"):
        def read(name):
            tum = read_tum(os.path.join(out, name + ".tum.txt"))
            return tum if fmt == "tum" else read_kitti(os.path.join(out, f"{name}.kitti.txt"), tum)

        rot, trans, pairs = mean_relative_error(read("camera_estimate"), read("camera_ground_truth"))
        camera = metrics["camera"]
        check(pairs == camera["pairs"] and close(rot, camera["mean_rot_deg"]) and
              close(trans, camera["mean_trans_m"]),
              f"{formulation} {fmt}: camera RPE {rot} deg {trans} m over {pairs} pairs, "
              f"summary.json {camera}")
        objects = sorted({n.split("_")[1] for n in names if n.startswith("object_")})
        check(len(objects) > 0, f"{formulation}: object files written")
        if not metrics["object_centric"]:
            continue  # world-centric object poses restart at each segment's true start (SPEC §5)
        # SPEC §5 counts the pairs (k−1, k) that have a motion H_k: not a pair that straddles two
        # segments of an object (a break with no gap), which the trajectory files cannot show.
        with open(os.path.join(out, "motions.csv")) as f:
            motions = [line.split(",")[:2] for line in f.read().split("\n")[1:] if line]
        per_object = {}
        for j in objects:
            frames = {int(k) for o, k in motions if o == j}
            per_object[j] = mean_relative_error(read(f"object_{j}_estimate"),
                                                read(f"object_{j}_ground_truth"), frames)
        expected = metrics["object_pose"]["per_object"]
        for j, (rot, trans, pairs) in per_object.items():
            if pairs == 0:
                continue
            check(j in expected and pairs == expected[j]["pairs"] and
                  close(rot, expected[j]["mean_rot_deg"]) and
                  close(trans, expected[j]["mean_trans_m"]),
                  f"{formulation} {fmt}: object {j} pose error {rot} {trans} over {pairs}, "
                  f"summary.json {expected.get(j)}")


def main():
    with tempfile.TemporaryDirectory() as work:
        for formulation in ("wc", "oc_b"):
            check_scene(formulation, work)
    print(f"{len(failures)} failures")
    return min(len(failures), 100)


if __name__ == "__main__":
    sys.exit(main())
