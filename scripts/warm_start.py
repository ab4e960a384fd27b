#!/usr/bin/python3
"""Starts a graph file from another solve: every vertex of GRAPH that SOLUTION also has (same id)
takes SOLUTION's value; everything else (edges, labels, other vertices) is copied unchanged.

    scripts/warm_start.py GRAPH SOLUTION OUT

For example oc_b from oc_a's solution (both built from one front-end file by `dynslam compare`
share their vertex ids; docs/CONVERGENCE.md on local minima):

    scripts/warm_start.py out/demo/kitti_0004/oc_b/graph.g2o \\
        out/demo/kitti_0004/oc_a/solution.g2o /tmp/oc_b_warm.g2o
    build/release/apps/dynslam solve /tmp/oc_b_warm.g2o --gt out/demo/kitti_0004/frontend.gt.txt \\
        --out /tmp/oc_b_warm
"""
import sys

VERTEX_TAGS = ("VERTEX_SE3:QUAT", "VERTEX_TRACKXYZ")


def vertex_id(line):
    fields = line.split()
    return fields[1] if len(fields) > 1 and fields[0] in VERTEX_TAGS else None


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    graph, solution, out = sys.argv[1:]
    values = {}
    with open(solution) as f:
        for line in f:
            vid = vertex_id(line)
            if vid is not None:
                values[vid] = line
    replaced = 0
    with open(graph) as f, open(out, "w") as o:
        for number, line in enumerate(f, start=1):
            vid = vertex_id(line)
            if vid in values:
                if values[vid].split()[0] != line.split()[0]:
                    sys.exit(f"{graph}:{number}: vertex {vid} is a {line.split()[0]} here but a "
                             f"{values[vid].split()[0]} in {solution}")
                line = values[vid]
                replaced += 1
            o.write(line)
    print(f"{out}: {replaced} vertices from {solution}", file=sys.stderr)


if __name__ == "__main__":
    main()
