"""Where the package finds the dynslam command and the embedded KITTI Tracking data."""
import os
import re
import shutil
import subprocess

_PACKAGE = os.path.dirname(os.path.abspath(__file__))


class ToolNotFound(Exception):
    pass


def find_cli():
    """The `dynslam` command: $DYNSLAM_CLI, the one installed beside this package
    (scripts/install_python_module), the build tree's, or the one on PATH."""
    candidates = [os.environ.get("DYNSLAM_CLI"),
                  os.path.join(_PACKAGE, "bin", "dynslam"),
                  os.path.join(_PACKAGE, "..", "..", "apps", "dynslam"),  # build/<type>/python/
                  shutil.which("dynslam")]
    for candidate in candidates:
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    raise ToolNotFound("no dynslam command: set DYNSLAM_CLI, or run scripts/install_python_module")


def embedded_kitti():
    """The KITTI Tracking ground truth shipped with dynslam (oxts/, label_02/, calib/):
    $DYNSLAM_KITTI, else the installed package's data/kitti_tracking, else the repository's
    above a module in its build tree; None when there is none."""
    candidates = [os.environ.get("DYNSLAM_KITTI"),
                  os.path.join(_PACKAGE, "data", "kitti_tracking"),
                  os.path.join(_PACKAGE, "..", "..", "..", "..", "data", "kitti_tracking")]
    for candidate in candidates:
        if candidate and os.path.isdir(os.path.join(candidate, "label_02")):
            return os.path.abspath(candidate)
    return None


def simulate_defaults(cli):
    """`dynslam simulate`'s options and their defaults, from the Simulation options table that
    `dynslam options` prints (docs/OPTIONS.md): {"pixel_sigma": "0.5", "noise": "on", …}."""
    result = subprocess.run([cli, "options"], capture_output=True, text=True)
    defaults, inside = {}, False
    for line in result.stdout.splitlines():
        if line.startswith("## "):
            inside = line.startswith("## Simulation options")
        row = re.match(r"\| `([a-z0-9_]+)` \| `--[a-z0-9-]+` \| [^|]* \| `([^`]*)` \|", line)
        if inside and row:
            defaults[row.group(1)] = row.group(2)
    return defaults
