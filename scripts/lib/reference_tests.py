"""reference_tests.py LASTTEST_LOG: counts the reference tests of a ctest run (SPEC §6: those
named Reference…, or of the reference and gtsam labels' files) and how many were skipped.

Prints one line; exit 1 when any was skipped (the reference suite is in data/: none may be).
"""
import re
import sys

REFERENCE = re.compile(r"Reference|reference|Covariance|gtsam", re.IGNORECASE)


def blocks(text):
    """(test name, its output) of each test in ctest's LastTest.log."""
    for match in re.finditer(r"^\d+/\d+ Testing: ([^\n]+)\n(.*?)(?=^\d+/\d+ Testing: |\Z)", text,
                             re.MULTILINE | re.DOTALL):
        yield match.group(1), match.group(2)


def main(path):
    with open(path, errors="replace") as f:
        text = f.read()
    ran = skipped = 0
    names = []
    for name, output in blocks(text):
        if not REFERENCE.search(name):
            continue
        ran += 1
        if "[  SKIPPED ]" in output or "Test Skipped" in output:
            skipped += 1
            names.append(name)
    print(f"reference tests (data/reference, SPEC §6): {ran} ran, {skipped} skipped"
          + (": " + ", ".join(names[:5]) if names else ""))
    return 1 if skipped else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
