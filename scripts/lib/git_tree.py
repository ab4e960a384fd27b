"""git_tree.py GIT_DIR REF OUT: writes the files of REF in GIT_DIR under OUT (scripts/build_gtsam).

Unlike `git archive`, a blob the git directory does not hold (a partial clone's large example
data) is skipped and counted instead of failing the whole tree.
"""
import os
import subprocess
import sys


def entries(git_dir, ref):
    """(mode, sha, path) of every blob of REF."""
    listing = subprocess.run(["git", "--git-dir", git_dir, "ls-tree", "-r", "-z", ref],
                             check=True, capture_output=True).stdout.decode()
    for entry in filter(None, listing.split("\0")):
        meta, path = entry.split("\t", 1)
        mode, kind, sha = meta.split()
        if kind == "blob":
            yield mode, sha, path


def write(path, mode, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if mode == "120000":
        os.symlink(data.decode(), path)
        return
    with open(path, "wb") as out:
        out.write(data)
    if mode == "100755":
        os.chmod(path, 0o755)


def main(git_dir, ref, out):
    batch = subprocess.Popen(["git", "--git-dir", git_dir, "cat-file", "--batch"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    written, absent = 0, 0
    for mode, sha, path in entries(git_dir, ref):
        batch.stdin.write(sha.encode() + b"\n")
        batch.stdin.flush()
        header = batch.stdout.readline().split()
        if header[-1] == b"missing":
            absent += 1
            continue
        data = batch.stdout.read(int(header[2]))
        batch.stdout.read(1)  # the newline after each object
        write(os.path.join(out, path), mode, data)
        written += 1
    batch.stdin.close()
    batch.wait()
    print(f"{ref}: {written} files written, {absent} absent from {git_dir} skipped")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
