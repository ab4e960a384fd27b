#!/usr/bin/env bash
# README.md's quick starts run as written (issue 43), so that they cannot rot: the ```sh block
# with the built `dynslam` on PATH, the ```python block with the built module, and the ```cpp
# block, which must be examples/quick_start.cc word for word, run on the scene the first made.
#   readme_test.sh DYNSLAM ROOT PYTHONPATH QUICK_START [PYTHON]
set -u
dynslam="$1" root="$2" python_path="$3" quick_start="$4" python="${5:-/usr/bin/python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failed=0

block() {  # the first fenced block of language $1 in README.md
  awk -v fence='```'"$1" '$0 == fence {on = 1; next} on && $0 == "```" {exit} on' "$root/README.md"
}
fail() { failed=$((failed + 1)); echo "FAIL: $1"; [ -f "$2" ] && tail -5 "$2"; }

mkdir "$work/bin"
ln -s "$dynslam" "$work/bin/dynslam"
[ -n "$(block sh)" ] || fail "README.md has no sh block" /dev/null
(cd "$work" && PATH="$work/bin:$PATH" bash -euo pipefail -c "$(block sh)") > "$work/sh.out" 2>&1 ||
  fail "the command-line quick start" "$work/sh.out"
grep -q "Table I" "$work/sh.out" || fail "compare printed no Table I" "$work/sh.out"
[ -s "$work/oc_b/covariances.csv" ] || fail "solve wrote no covariances.csv" "$work/sh.out"

(cd "$work" && PYTHONPATH="$python_path" "$python" -c "$(block python)") > "$work/py.out" 2>&1 ||
  fail "the Python quick start" "$work/py.out"
[ "$(grep -cE '^(wc|oc_b) [0-9]+ steps [0-9.]+ deg$' "$work/py.out")" = 2 ] ||
  fail "the Python quick start printed no line per formulation" "$work/py.out"

block cpp | diff - "$root/examples/quick_start.cc" > "$work/cpp.diff" ||
  fail "README's C++ quick start is not examples/quick_start.cc" "$work/cpp.diff"
(cd "$work" && "$quick_start" scene.g2o scene.gt.txt) > "$work/cpp.out" 2>&1 ||
  fail "examples/quick_start" "$work/cpp.out"
[ "$(grep -c 'steps, object motion error' "$work/cpp.out")" = 5 ] ||
  fail "quick_start printed no line per formulation" "$work/cpp.out"

[ "$failed" = 0 ] && echo "readme: every quick start ran"
exit "$failed"
