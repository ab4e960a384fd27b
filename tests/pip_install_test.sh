#!/usr/bin/env bash
# `pip install .` into a fresh venv that sees Debian's NumPy (issue 44), from the source tree and
# without a package index (pyproject.toml, python/build_backend/): the package imports, knows
# its version, finds its KITTI data and its command; `pip install -e .` too. The build tree
# given is reused, so this checks the packaging, not a second build.
#   pip_install_test.sh ROOT BUILD_DIR [PYTHON]
set -euo pipefail
root="$1" build="$2" python="${3:-/usr/bin/python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export DYNSLAM_BUILD_DIR="$build" PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1

"$python" -m venv --system-site-packages "$work/v"
(cd "$root" && "$work/v/bin/pip" install -q .)
(cd "$work" && "$work/v/bin/python" -c "import dynslam; print(dynslam.__version__)") > "$work/version"
grep -qE '^[0-9]+\.[0-9]+\.[0-9]+$' "$work/version"
(cd "$work" && "$work/v/bin/python" - <<'PY')
import os
import sys
import dynslam
assert dynslam.__file__.startswith(sys.prefix), dynslam.__file__  # the venv's copy
assert os.path.isdir(os.path.join(dynslam.embedded_kitti_dir(), "label_02"))
frontend, gt = dynslam.simulate(sequence="0003", frames="0:5", seed=1)
assert dynslam.solve(dynslam.build(frontend, "wc", gt), max_iterations=3).steps >= 1
PY
"$work/v/bin/dynslam" --version | grep -q "^dynslam $(cat "$work/version")"

"$python" -m venv --system-site-packages "$work/e"
(cd "$root" && "$work/e/bin/pip" install -q -e .)
(cd "$work" && "$work/e/bin/python" -c "import dynslam; print(dynslam.__file__)") | grep -q "^$build/python/dynslam/"
echo "pip install . and pip install -e . into venvs: imported dynslam $(cat "$work/version")"
