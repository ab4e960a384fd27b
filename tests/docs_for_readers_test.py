#!/usr/bin/python3
"""The user-facing docs and the public headers are for readers: no commit hashes, no "issue N"
and no dates of sessions (measurements, with their dates and commands, live in docs/results/).

    tests/docs_for_readers_test.py SOURCE_DIR      # exit 1 listing every FILE:LINE found
"""
import glob
import os
import re
import sys

USER_DOCS = ["README.md", "docs/GUIDE.md", "docs/OPTIONS.md", "docs/PYTHON.md", "docs/API.md",
             "docs/SWEEPS.md", "docs/COVARIANCE.md", "docs/ARCHITECTURE.md", "docs/SPEC.md",
             "docs/SIMULATOR.md", "docs/GTSAM_BACKEND.md"]
FORBIDDEN = [
    ("a commit hash", re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*[0-9])[0-9a-f]{7,40}\b")),
    ("an issue number", re.compile(r"\bissues? #?\d+", re.I)),
    ("a date", re.compile(r"\b20\d\d-\d\d-\d\d\b")),
]


def findings(root):
    files = USER_DOCS + sorted(os.path.relpath(p, root) for p in
                               glob.glob(os.path.join(root, "include", "dynslam", "*.h")))
    for name in files:
        with open(os.path.join(root, name), encoding="utf-8") as f:
            for number, line in enumerate(f, start=1):
                for what, pattern in FORBIDDEN:
                    for match in pattern.finditer(line):
                        yield f"{name}:{number}: {what} ({match.group(0)})"


def main():
    found = list(findings(sys.argv[1] if len(sys.argv) > 1 else "."))
    for line in found:
        print(line)
    print(f"{len(found)} found in the user-facing docs and public headers")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
