"""unpack_data.py SOURCE TARGET: the data tree SOURCE as plain files under TARGET.

FILE.xz becomes FILE (decompressed when missing or older than FILE.xz); every other file is a
symbolic link to its source. Run by CMake at configure time so that the tests read one complete
tree (scripts/make_reference says which files are compressed and why). Files under TARGET that
no longer have a source are removed.
"""
import lzma
import os
import shutil
import sys


def unpack(source, target):
    wanted = set()
    for folder, _, files in os.walk(source):
        out_folder = os.path.join(target, os.path.relpath(folder, source))
        os.makedirs(out_folder, exist_ok=True)
        for name in files:
            src = os.path.join(folder, name)
            if name.endswith(".xz"):
                dest = os.path.join(out_folder, name[:-3])
                if not os.path.exists(dest) or os.path.getmtime(dest) < os.path.getmtime(src):
                    with lzma.open(src, "rb") as f_in, open(dest + ".part", "wb") as f_out:
                        shutil.copyfileobj(f_in, f_out)
                    os.replace(dest + ".part", dest)
            else:
                dest = os.path.join(out_folder, name)
                if os.path.islink(dest) and os.readlink(dest) == src:
                    wanted.add(dest)
                    continue
                if os.path.lexists(dest):
                    os.remove(dest)
                os.symlink(src, dest)
            wanted.add(dest)
    for folder, _, files in os.walk(target):
        for name in files:
            path = os.path.join(folder, name)
            if path not in wanted:
                os.remove(path)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    unpack(os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]))
