#!/usr/bin/env bash
# The `dynslam` command as a user meets it: exit codes 0/1/2 (docs/STYLE.md), errors that name
# the file and line, outputs of SPEC §4. Usage: cli_test.sh DYNSLAM_BINARY REPOSITORY_ROOT
set -u
dynslam="$1"
root="$2"
data="$root/data/reference"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
passed=0
failed=0

check() {  # description expected_exit command…   (stdout+stderr in $work/out)
  local description="$1" expected="$2"
  shift 2
  "$@" >"$work/out" 2>&1
  local code=$?
  if [ "$code" -eq "$expected" ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $description: exit $code, expected $expected"
    head -5 "$work/out"
  fi
}
expect_output() {  # description pattern
  if grep -q -- "$2" "$work/out"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $1: output lacks '$2'"
    head -5 "$work/out"
  fi
}
expect_no_traceback() {  # description
  if grep -q Traceback "$work/out"; then
    failed=$((failed + 1))
    echo "FAIL: $1 printed a traceback"
  else
    passed=$((passed + 1))
  fi
}

check "no command" 2 "$dynslam"
check "top-level help" 0 "$dynslam" --help
check "unknown command" 2 "$dynslam" frobnicate
check "--version" 0 "$dynslam" --version
expect_output "--version names the version and the commit" "^dynslam [0-9][0-9.]* (git [0-9a-f]"
check "--check-options of good options" 0 "$dynslam" solve - --check-options --tolerances tight --max-iterations 5
check "--check-options of a bad value" 2 "$dynslam" solve - --check-options --minimizer newton
expect_output "--check-options names the option" "minimizer"
check "--check-options of a bad combination" 2 "$dynslam" solve - --check-options --tolerances tight --extrapolation on
for command in solve build compare metrics verify; do
  check "$command --help" 0 "$dynslam" "$command" --help
  expect_output "$command --help lists defaults" "default:"
done
check "unknown option" 2 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --out "$work/x" --linear-solver cholmod
expect_output "unknown option value" "is not one of"
check "missing file" 2 "$dynslam" solve "$work/missing.g2o" --out "$work/x"
expect_output "missing file named" "missing.g2o"
check "--tolerances tight with a --remaining-chi2 rule is a usage error" 2 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --out "$work/x" --tolerances tight --remaining-chi2 0.1
expect_output "the usage error names both options" "--tolerances tight sets --remaining-chi2 0; give one of them"
check "--tolerances tight with --extrapolation on is a usage error" 2 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --out "$work/x" --tolerances tight --extrapolation on
expect_output "the usage error names both options" "--tolerances tight sets --extrapolation off; give one of them"

printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_TRACKXYZ 1 0 zero 0\n' >"$work/bad.g2o"
check "bad number" 2 "$dynslam" solve "$work/bad.g2o" --out "$work/x"
expect_output "bad number names file and line" "bad.g2o:2: VERTEX_TRACKXYZ: field 3 'zero' is not a number"

head -3 "$data/posegraph_parking-garage/graphs/pose_graph.g2o" >"$work/noprior.g2o"
grep -m1 EDGE_SE3:QUAT "$data/posegraph_parking-garage/graphs/pose_graph.g2o" >>"$work/noprior.g2o"
check "gauge freedom refused" 2 "$dynslam" solve "$work/noprior.g2o" --out "$work/x"
expect_output "gauge freedom explained" "fix-first"
check "gauge fixed with --fix-first" 0 "$dynslam" solve "$work/noprior.g2o" --out "$work/fixed" --fix-first

printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 -1 0 1\n' >"$work/indefinite.g2o"
check "indefinite information refused" 2 "$dynslam" solve "$work/indefinite.g2o" --out "$work/x"
expect_output "indefinite information names file and line" "indefinite.g2o:4: EDGE_SE3_TRACKXYZ: the information matrix (fields 6 to 11) is not symmetric positive definite"
check "indefinite information repaired on request" 0 "$dynslam" solve "$work/indefinite.g2o" --out "$work/repaired" --repair-information
expect_output "repair reported" "^warning: --repair-information: repaired the information matrices of 1 edges (first: .*indefinite.g2o:4)"

printf 'VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n' >"$work/no_edges.g2o"
check "a graph with no edges is refused" 2 "$dynslam" solve "$work/no_edges.g2o" --out "$work/x" --fix-first
expect_output "no edges explained" "nothing to solve"

check "solve" 0 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --gt "$data/synthetic/gt.txt" --out "$work/wc"
for file in solution.g2o cameras.csv motions.csv object_poses.csv convergence.csv summary.json; do
  if [ -s "$work/wc/$file" ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: solve wrote no $file"; fi
done
# scripts/plot_trajectory.py on that solve output; bad input is file:line and exit 1, no traceback.
if /usr/bin/python3 -c "import matplotlib" >/dev/null 2>&1; then
  plot="$root/scripts/plot_trajectory.py"
  check "plot_trajectory" 0 "$plot" "$work/wc" --gt "$data/synthetic/gt.txt" --labels wc --out "$work/trajectory.png"
  if [ -s "$work/trajectory.png" ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: plot_trajectory wrote no PNG"; fi
  mkdir -p "$work/bad csv"
  cp "$work/wc/cameras.csv" "$work/wc/object_poses.csv" "$work/bad csv/"
  sed -i '3s/.*/1,0.1,zero,0.3,0,0,0,1/' "$work/bad csv/cameras.csv"
  check "plot_trajectory: malformed cameras.csv" 1 "$plot" "$work/bad csv" --out "$work/bad.png"
  expect_output "malformed cameras.csv names file and line" "bad csv/cameras.csv:3: field 'zero' is not a finite number"
  expect_no_traceback "plot_trajectory"
  # The other two plot scripts: a file that cannot be read or written is one line, exit 1.
  check "plot_convergence: missing file" 1 "$root/scripts/plot_convergence.py" "$work/missing.csv" --out "$work/c.png"
  expect_output "missing convergence.csv named" "missing.csv: cannot read the file: No such file or directory"
  expect_no_traceback "plot_convergence"
  check "plot_errors: unwritable image" 1 "$root/scripts/plot_errors.py" "$work/wc/errors.csv" --out "$work/no dir/e.png"
  expect_output "unwritable errors image named" "no dir/e.png: cannot write the image"
  expect_no_traceback "plot_errors"
  check "compare draws its plots" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare" --formulations wc
  for file in convergence.png trajectory.png errors.png wc/errors.csv; do
    if [ -s "$work/compare/$file" ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: compare drew no $file"; fi
  done
  # A plot that cannot be drawn is one warning with the script's reason; the other plots and
  # the tables stand.
  mkdir -p "$work/failing scripts"
  cp "$root/scripts/plot_compare.py" "$root/scripts/plot_trajectory.py" "$root/scripts/plot_errors.py" "$work/failing scripts/"
  printf 'import sys\n\n\ndef draw(*args):\n    sys.exit("plot failed on purpose")\n' >"$work/failing scripts/plot_convergence.py"
  check "compare with a failing plot" 0 env DYNSLAM_SCRIPTS_DIR="$work/failing scripts" "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_noplot" --formulations wc
  if grep -q "^warning: no convergence.png: plot failed on purpose" "$work/out" && [ -s "$work/compare_noplot/tables.md" ] &&
     [ -s "$work/compare_noplot/trajectory.png" ] && [ ! -e "$work/compare_noplot/convergence.png" ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); echo "FAIL: compare with a failing plot:"; tail -3 "$work/out"
  fi
else
  echo "SKIP: plot cases (/usr/bin/python3 cannot import matplotlib)"
fi
check "simulate --density paper" 0 "$dynslam" simulate --kitti "$root/data/kitti_tracking" --seq 0002 --frames 0:5 --density paper --out "$work/paper"
check "simulate --density paper needs a sequence of the paper" 2 "$dynslam" simulate --synthetic --density paper --out "$work/paper"
check "--density paper and --static-points conflict" 2 "$dynslam" simulate --kitti "$root/data/kitti_tracking" --seq 0002 --frames 0:5 --density paper --static-points 10 --out "$work/paper"
check "compare without ground truth" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --out "$work/compare_nogt" --formulations wc,oc_b
expect_output "compare without ground truth says what needs it" "need ground truth"
if [ "$(grep -c '| needs --gt | needs --gt |' "$work/compare_nogt/tables.md")" = 2 ] &&
   [ -s "$work/compare_nogt/convergence.png" ] && [ ! -e "$work/compare_nogt/errors.png" ] && [ ! -e "$work/compare_nogt/oc_b/errors.csv" ] &&
   ! grep -q '"metrics"' "$work/compare_nogt/oc_b/summary.json" &&
   grep -q 'centroid rule' "$work/compare_nogt/oc_b/summary.json"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: compare without ground truth: tables, plot or summary"
fi
check "compare without the plot scripts warns and succeeds" 0 env DYNSLAM_SCRIPTS_DIR="$work/none" "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_noscripts" --formulations wc
expect_output "missing plot scripts give a warning" "^warning: "
check "compare --no-plots" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_noplots" --formulations wc --no-plots
if grep -q "^warning: " "$work/out" || [ -e "$work/compare_noplots/trajectory.png" ]; then failed=$((failed + 1)); echo "FAIL: compare --no-plots plotted or warned"; else passed=$((passed + 1)); fi

check "verify a default solve against GTSAM tight_exact" 0 "$dynslam" verify "$work/wc" "$data/synthetic/gtsam/wc/tight_exact" --report-variables
expect_output "verify passes" "^PASS"
check "verify beyond tolerance exits 1" 1 "$dynslam" verify "$work/wc" "$data/synthetic/gtsam/wc/tight_exact" --translation-tolerance 1e-12
expect_output "verify names the worst variable" "worst vertex"
check "verify --report-variables reports the variables without failing on them" 0 "$dynslam" verify "$work/wc" "$data/synthetic/gtsam/wc/tight_exact" --translation-tolerance 1e-12 --report-variables
expect_output "verify --report-variables marks the variable over tolerance" "(info, over)"
check "verify against another graph is bad input" 2 "$dynslam" verify "$work/wc" "$data/synthetic/gtsam/oc_b/tight_exact"
expect_output "verify names the missing vertex" "has no vertex"
check "a solve stopped by the iteration limit is still usable" 0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/limit" --max-iterations 2
check "build" 0 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation oc_b --gt "$data/synthetic/gt.txt" --out "$work/oc_b.g2o"
expect_output "build report" "kept: object 1 frames 0..29"
check "build --start from a solved wc graph (SPEC §3.5)" 0 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation oc_b --gt "$data/synthetic/gt.txt" --start "$work/wc/solution.g2o" --out "$work/oc_b_start.g2o"
expect_output "build --start reported" "initial values from .*solution.g2o"
if cmp -s <(grep '^EDGE' "$work/oc_b.g2o") <(grep '^EDGE' "$work/oc_b_start.g2o") &&
   ! cmp -s <(grep '^VERTEX' "$work/oc_b.g2o") <(grep '^VERTEX' "$work/oc_b_start.g2o"); then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: build --start changed the edges or kept the front end's values"
fi
check "build --start from an oc graph is bad input" 2 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation oc_b --start "$work/oc_b.g2o" --out "$work/x.g2o"
expect_output "build --start names the file and what it needs" "oc_b.g2o: not the wc graph of this front end"
check "build --start for wc is a usage error" 2 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation wc --start "$work/wc/solution.g2o" --out "$work/x.g2o"
expect_output "build --start says which formulations" "applies to oc_a, oc_b and oc_c, not wc"
check "build --start from a missing file" 2 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation oc_a --start "$work/missing.g2o" --out "$work/x.g2o"
expect_output "build --start names the missing file" "missing.g2o"
check "compare --start wc without wc first is a usage error" 2 "$dynslam" compare "$data/synthetic/frontend.g2o" --out "$work/x" --formulations oc_b --start wc
expect_output "compare --start wc says why" "wc must come first"
check "compare --start wc" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_start" --formulations wc,oc_b --start wc --no-plots
if grep -q "^(--start wc" "$work/compare_start/tables.md" &&
   grep -q "initial values from wc's solution" "$work/compare_start/oc_b/build.txt"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: compare --start wc: tables.md or oc_b/build.txt does not say so"
fi
# Not on a terminal, compare prints one line per formulation; --verbose adds a line per step.
if [ "$(grep -c '^\[compare\]' "$work/out")" = 2 ] && ! grep -q '^step ' "$work/out"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: compare printed more than a line per formulation"; cat "$work/out"
fi
check "compare --verbose" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_verbose" --formulations wc --no-plots --no-report --verbose
expect_output "compare --verbose prints the steps" "^step    1 "
expect_output "compare --verbose names the solve" "1/1 wc: solving"
if [ ! -e "$work/compare_verbose/report.html" ]; then passed=$((passed + 1)); else
  failed=$((failed + 1)); echo "FAIL: compare --no-report wrote report.html"; fi
# --resume reads finished solves back (the same tables, with a note); other options solve again.
cp "$work/compare_start/tables.md" "$work/start_tables.md"
check "compare --resume" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_start" --formulations wc,oc_b --start wc --no-plots --resume
expect_output "compare --resume reuses wc" "wc: the finished solve in .* reused"
expect_output "compare --resume reuses oc_b" "oc_b: the finished solve in .* reused"
if grep -q "^(--resume: wc, oc_b read back" "$work/compare_start/tables.md" &&
   [ "$(tail -n +3 "$work/compare_start/tables.md")" = "$(cat "$work/start_tables.md")" ]; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: compare --resume: tables.md differs from the run it resumed"
fi
check "compare --resume with other solver options" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_start" --formulations wc,oc_b --start wc --no-plots --resume --max-iterations 400
expect_output "compare --resume solves again when the options differ" "oc_b: [a-z_]*, [0-9]* steps, .*[0-9] s;"
echo "{" > "$work/compare_start/oc_b/summary.json"
check "compare --resume after a broken summary.json" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_start" --formulations wc,oc_b --start wc --no-plots --resume --max-iterations 400
expect_output "compare --resume keeps wc" "wc: the finished solve in .* reused"
expect_output "compare --resume solves oc_b again" "oc_b: [a-z_]*, [0-9]* steps, .*[0-9] s;"
# A graph.g2o one byte longer or shorter than the rebuild is another graph: solved again.
for edit in "append" "truncate"; do
  if [ "$edit" = append ]; then echo "#" >> "$work/compare_start/wc/graph.g2o"
  else truncate -s -1 "$work/compare_start/wc/graph.g2o"; fi
  check "compare --resume after wc/graph.g2o changed ($edit)" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/compare_start" --formulations wc,oc_b --start wc --no-plots --resume --max-iterations 400
  expect_output "compare --resume solves wc again when its graph differs ($edit)" "wc: [a-z_]*, [0-9]* steps, .*[0-9] s;"
done
check "metrics" 0 "$dynslam" metrics "$work/wc/solution.g2o" "$data/synthetic/gt.txt"
check "bad --compat" 2 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --out "$work/x" --compat 9
check "bad --compat dynosam item" 2 "$dynslam" solve "$data/synthetic/graphs/wc.g2o" --out "$work/x" --compat dynosam:5
expect_output "bad dynosam item named" "'5' is not a DynoSAM item number 1 to 4"
check "build hy with --compat dynosam" 0 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation hy --gt "$data/synthetic/gt.txt" --compat dynosam --out "$work/hy.g2o"
check "bad --hybrid-smoothing-info" 2 "$dynslam" build "$data/synthetic/frontend.g2o" --formulation hy --hybrid-smoothing-info 0.01 --out "$work/x.g2o"
expect_output "bad smoothing information named" "is not frontend, world or two positive sigmas"
check "solve hy with DynoSAM's Huber (item 2)" 0 "$dynslam" solve "$work/hy.g2o" --out "$work/hy" --compat dynosam:2 --max-iterations 2
if grep -q '"robust": "hybrid_point=huber:1e-04"' "$work/hy/summary.json"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: --compat dynosam:2 did not put Huber 1e-4 on hybrid_point edges"
fi
check "solve with one compatibility item as its own option" 0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/released" --dsc-released-lm on --max-iterations 2
if grep -q '"dsc_released_lm": true' "$work/released/summary.json"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: --dsc-released-lm on was not used (summary.json's solver block)"
fi

# docs/OPTIONS.md is what `dynslam options` prints from the option tables (issue 43): the list
# cannot fall behind the code.
if "$dynslam" options | cmp -s - "$root/docs/OPTIONS.md"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: docs/OPTIONS.md differs from 'dynslam options' (regenerate: dynslam options > docs/OPTIONS.md)"
fi
check "solve --help groups its options" 0 "$dynslam" solve --help
expect_output "the stopping group lists --remaining-chi2" "^stopping:"
expect_output "two examples" "^examples:"

# simulate finds the embedded KITTI data from wherever it is run.
check "simulate --seq 0003 from another directory" 0 env -C "$work" "$dynslam" simulate --seq 0003 --frames 0:5 --out "$work/anywhere"
if [ -s "$work/anywhere.g2o" ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: simulate from another directory wrote nothing"; fi

# Marginal covariances (docs/COVARIANCE.md): a row per requested variable; an unknown kind is a
# usage error before any solve; a later solve without --covariance leaves no stale file.
check "--covariance cameras,motions" 0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/cov" --covariance cameras,motions
expect_output "--covariance says what it wrote" "covariances: .* variables"
rows=$(($(wc -l <"$work/cov/covariances.csv") - 1))
expected=$(($(wc -l <"$work/cov/cameras.csv") - 1 + $(wc -l <"$work/cov/motions.csv") - 1))
if [ "$rows" -eq "$expected" ] && grep -q '"covariance"' "$work/cov/summary.json"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: covariances.csv has $rows rows, expected $expected (cameras + motions)"
fi
check "--covariance with an unknown kind" 2 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/cov" --covariance cameras,poses
expect_output "the unknown kind is named" "unknown kind 'poses'"
check "a solve without --covariance" 0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/cov" --max-iterations 3
if [ ! -e "$work/cov/covariances.csv" ]; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: an earlier solve's covariances.csv was left beside a solve without --covariance"
fi

check "compare --covariance with --gt" 0 "$dynslam" compare "$data/synthetic/frontend.g2o" --gt "$data/synthetic/gt.txt" --out "$work/cmp_cov" --formulations wc,oc_b --no-plots --covariance cameras,motions,object_poses
if grep -q "^### NEES" "$work/cmp_cov/tables.md" && grep -q "^NEES,oc_b,,object_pose," "$work/cmp_cov/tables.csv" && [ -s "$work/cmp_cov/oc_b/covariances.csv" ]; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: compare --covariance wrote no NEES table or covariances.csv"
fi
check "compare --covariance with --resume" 2 "$dynslam" compare "$data/synthetic/frontend.g2o" --out "$work/cmp_cov" --covariance all --resume
expect_output "the conflict is named" "covariance and --resume"

# The huge-page heap (process/huge_page_heap.h) changes where blocks live, never what is computed.
check "solve with the huge-page heap" 0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/heap_on" --max-iterations 5
check "solve without it" 0 env DYNSLAM_HUGE_PAGES=0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/heap_off" --max-iterations 5
if cmp -s "$work/heap_on/solution.g2o" "$work/heap_off/solution.g2o"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: DYNSLAM_HUGE_PAGES=0 changed the solution"
fi

# So do the inline OpenMP regions (process/inline_openmp_regions.h): CHOLMOD computes the same.
check "solve with libgomp's regions" 0 env DYNSLAM_INLINE_OPENMP=0 "$dynslam" solve "$data/synthetic/graphs/oc_b.g2o" --out "$work/regions_libgomp" --max-iterations 5
if cmp -s "$work/heap_on/solution.g2o" "$work/regions_libgomp/solution.g2o"; then
  passed=$((passed + 1))
else
  failed=$((failed + 1)); echo "FAIL: DYNSLAM_INLINE_OPENMP=0 changed the solution"
fi

echo "cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
