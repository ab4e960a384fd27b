#!/usr/bin/python3
"""Turns the CSVs of benchmarks/sweep.py into docs/BENCHMARKS.md and its plots (generated, never
typed: edit this script, not the Markdown).

    benchmarks/report.py [--runs out/benchmarks] [--out docs/BENCHMARKS.md]
"""
import argparse
import collections
import csv
import datetime
import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import gtsam_ratios  # noqa: E402  (beside this script)

ROOT = pathlib.Path(__file__).resolve().parent.parent


def read(path):
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def short(graph):
    p = pathlib.Path(graph)
    return f"{p.parent.parent.name}/{p.stem}" if p.parent.name == "graphs" else p.stem


def fmt(x, digits=3):
    return "—" if x is None else f"{x:.{digits}g}"


def fit_exponent(xs, ys):
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def per_step(run, field):
    """`field` of a default run per step (time_per_step is already per step), or None."""
    if not run or not number(run[field]):
        return None
    steps = 1 if field == "time_per_step" else max(1, int(run["steps"]))
    return number(run[field]) / steps


def floor_table(runs, floors):
    by_graph = collections.defaultdict(dict)
    for f in floors:
        by_graph[f["graph"]][(f["matrix"], f["method"])] = f
    lines = ["| graph | matrix | n | nnz(L) | CHOLMOD simplicial (s) | CHOLMOD supernodal (s) | "
             "Eigen LDLT (s) | dynslam default: s per step | of which evaluation | of which "
             "linear solve | step / fastest factorisation | linear solve / fastest |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    default = {r["graph"]: r for r in runs if r["config"] == "default"}
    for graph, cells in by_graph.items():
        for matrix in ("normal", "reduced"):
            times = {m: number(cells[(matrix, m)]["seconds"]) for (mx, m) in cells if mx == matrix}
            any_row = cells[(matrix, "cholmod_simplicial")]
            fastest = min(t for t in times.values() if t)
            # The default (sparse normal Cholesky) factors the damped normal matrix on every graph:
            # its step is set against the `normal` rows.
            step = per_step(default.get(graph), "time_per_step") if matrix == "normal" else None
            evaluation = per_step(default.get(graph), "time_evaluation") if step else None
            linear = per_step(default.get(graph), "time_linear_solve") if step else None
            lines.append(
                f"| {short(graph)} | {matrix} | {any_row['n']} | {any_row['nnz_factor']} | "
                f"{fmt(times.get('cholmod_simplicial'))} | {fmt(times.get('cholmod_supernodal'))} | "
                f"{fmt(times.get('eigen_simplicial_ldlt'))} | {fmt(step) if step else ''} | "
                f"{fmt(evaluation) if step else ''} | {fmt(linear) if step else ''} | "
                f"{fmt(step / fastest, 2) if step else ''} | "
                f"{fmt(linear / fastest, 2) if step else ''} |")
    return lines


def sweep_tables(runs):
    lines = []
    by_graph = collections.defaultdict(list)
    for r in runs:
        by_graph[r["graph"]].append(r)
    for graph, rows in by_graph.items():
        lines += ["", f"### {short(graph)} ({rows[0]['variables']} variables, "
                  f"{rows[0]['edges']} edges)", "",
                  "| configuration | steps | total (s) | evaluation (s) | linear solve (s) | "
                  "s per step | to GTSAM released (s) | to optimum·(1+1e-6) (s) | final rel. to "
                  "optimum | termination |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            lines.append(
                f"| {r['config']} | {r['steps']} | {fmt(number(r['time_total']))} | "
                f"{fmt(number(r['time_evaluation']))} | {fmt(number(r['time_linear_solve']))} | "
                f"{fmt(number(r['time_per_step']))} | {fmt(number(r['time_to_released']))} | "
                f"{fmt(number(r['time_to_optimum_1e6']))} | {r['rel_to_optimum'] or '—'} | "
                f"{r['termination']} |")
    return lines


def fastest_table(runs):
    lines = ["| graph | fastest configuration to optimum·(1+1e-6) | time (s) | fastest with one "
             "thread | time (s) | default's time (s) | default / fastest with one thread |",
             "|---|---|---|---|---|---|---|"]
    by_graph = collections.defaultdict(list)
    for r in runs:
        by_graph[r["graph"]].append(r)
    to_optimum = lambda r: number(r["time_to_optimum_1e6"])
    for graph, rows in by_graph.items():
        reached = [r for r in rows if to_optimum(r) is not None]
        if not reached:
            continue
        best = min(reached, key=to_optimum)
        best_t1 = min((r for r in reached if str(r["threads"]) == "1"), key=to_optimum,
                      default=None)
        default = next((r for r in rows if r["config"] == "default"), None)
        default_time = to_optimum(default) if default else None
        t1_time = to_optimum(best_t1) if best_t1 else None
        lines.append(f"| {short(graph)} | {best['config']} | {fmt(to_optimum(best))} | "
                     f"{best_t1['config'] if best_t1 else '—'} | {fmt(t1_time)} | "
                     f"{fmt(default_time)} | "
                     f"{fmt(default_time / t1_time, 2) if default_time and t1_time else '—'} |")
    return lines


def scaling_section(rows, plot_path):
    if not rows:
        return ["(no scaling runs: `benchmarks/sweep.py --scaling`)"]
    lines = ["| scene | formulation | frames | variables | steps | s per step | total (s) | "
             "peak RSS (MB) | KB per variable |", "|---|---|---|---|---|---|---|---|---|"]
    series = collections.defaultdict(list)  # (scene, formulation) -> rows
    for r in rows:
        scene = "synthetic" if r["sequence"] == "synthetic" else f"KITTI {r['sequence']}"
        series[(scene, r["formulation"])].append(r)
        kb = number(r["peak_rss_mb"]) * 1024 / number(r["variables"])
        lines.append(f"| {scene} | {r['formulation']} | {r['frames']} | {r['variables']} | "
                     f"{r['steps']} | {fmt(number(r['time_per_step']))} | "
                     f"{fmt(number(r['time_total']))} | {r['peak_rss_mb']} | {kb:.2f} |")
    lines += ["", "Fitted exponents (least squares of log time against log variables):", ""]
    for (scene, formulation), rs in series.items():
        xs = [number(r["variables"]) for r in rs]
        per_step = fit_exponent(xs, [number(r["time_per_step"]) for r in rs])
        total = fit_exponent(xs, [number(r["time_total"]) for r in rs])
        lines.append(f"- {scene} {formulation}: time per step ∝ n^{per_step:.2f}, total time ∝ "
                     f"n^{total:.2f} ({fmt(min(xs))}–{fmt(max(xs))} variables)")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for (scene, formulation), rs in series.items():
            ax.loglog([number(r["variables"]) for r in rs],
                      [number(r["time_per_step"]) for r in rs], "o-",
                      label=f"{scene} {formulation}: per step")
        ax.set_xlabel("variables")
        ax.set_ylabel("seconds per step")
        ax.legend()
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(plot_path, dpi=120)
        lines += ["", f"![scaling]({plot_path.relative_to(plot_path.parent.parent)})"]
    except ImportError:
        lines += ["", "(matplotlib is not installed: no plot)"]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", default=str(ROOT / "out" / "benchmarks"))
    parser.add_argument("--out", default=str(ROOT / "docs" / "BENCHMARKS.md"))
    args = parser.parse_args()
    src = pathlib.Path(args.runs)
    runs, floors, scaling = read(src / "runs.csv"), read(src / "floor.csv"), read(src / "scaling.csv")
    sweeps = []
    if (src / "meta.json").exists():
        sweeps = json.loads((src / "meta.json").read_text()).get("sweeps", [])
    if not sweeps:
        sweeps = [{"command": "benchmarks/sweep.py --quick --scaling", "seconds": None}]
    seconds = [s["seconds"] for s in sweeps if s.get("seconds")]
    duration = (f"{sum(seconds) / 60:.0f} minutes on this machine" if len(seconds) == len(sweeps)
                else "duration not recorded for every sweep")
    if not runs:
        sys.exit(f"{src}/runs.csv: missing or empty (run benchmarks/sweep.py first)")
    out = pathlib.Path(args.out)
    plot_dir = out.parent / "benchmarks"
    plot_dir.mkdir(parents=True, exist_ok=True)
    text = [
        "# Benchmarks",
        "",
        "Generated by `benchmarks/report.py` from the CSVs of `benchmarks/sweep.py`; do not edit by "
        f"hand. Reproduce ({duration}):",
        "",
        "    cmake --build build/release --target dynslam_cli factorization_floor",
        *[f"    {s['command']}  # {s.get('date', 'date not recorded')}, "
          f"{s.get('machine', 'machine not recorded')}"
          for s in sweeps],
        f"    benchmarks/report.py --runs {src.resolve().relative_to(ROOT) if src.resolve().is_relative_to(ROOT) else src}",
        "",
        "(`benchmarks/sweep.py` writes `out/benchmarks/`; the data behind this page is kept in "
        "`docs/benchmarks/data/`." + (
            " The data was made by these sweeps in order; a `--scaling-only` sweep leaves runs.csv "
            "and floor.csv as they are and rewrites scaling.csv, or with `--append` adds to it; "
            "`--scaling` with the first command would remake the scaling rows too."
            if len(sweeps) > 1 else "") + ")",
        "",
        f"This page generated {datetime.date.today().isoformat()} on {gtsam_ratios.machine()}; "
        "each sweep's date and machine are beside its command above; one run per "
        "configuration, "
        "nothing else running. The sweep's own tables have no GTSAM column: GTSAM is timed "
        "beside dynslam, in one run, by `dynslam bench` with the GTSAM backend "
        "(docs/results/GTSAM.md).",
        "",
        "## The floor: one sparse Cholesky factorisation (target: a step ≤ 1.5× the fastest)",
        "",
        "`factorization_floor GRAPH` at the initial values, damping 1e-6·diag(JᵀJ); median of 5; "
        "fill-reducing analysis (AMD) not timed; CHOLMOD in one OpenMP thread with its regions "
        "run as plain calls, as `dynslam solve` runs it (docs/SOLVER.md \"OpenMP regions of one "
        "thread\"). `normal` is the matrix the default solver factors (sparse normal "
        "Cholesky on CHOLMOD); `reduced` has the static points eliminated (what sparse Schur "
        "factors on graphs with points; on pose graphs the same as `normal`). A step also "
        "evaluates residuals and Jacobians and forms JᵀJ, which the floor does not: per step, "
        "`evaluation` is Ceres's residual and Jacobian evaluation (autodiff Jets over the 7 "
        "ambient parameters of each pose, then the manifold's 7×6 Jacobian) and `linear solve` "
        "is forming JᵀJ, damping it and CHOLMOD's factorisation and solve. `linear solve / "
        "fastest` near 1 says the factorisation is at its floor and what is left is evaluation.",
        "",
        *floor_table(runs, floors),
        "",
        "## Fastest configuration per graph",
        "",
        *fastest_table(runs),
        "",
        "## Scaling (simulated KITTI 0020 and synthetic scenes of growing length; the defaults)",
        "",
        "`dynslam simulate --kitti data/kitti_tracking --seq 0020 --frames 0:N --seed 1` (at most "
        "837 frames: the whole sequence) or `dynslam simulate --synthetic --synthetic-frames N "
        "--seed 1` (the synthetic scene stretched to N frames, for the largest problems), `dynslam "
        "build` per formulation, then `dynslam solve` with the defaults (wc: dogleg, oc_b: LM; "
        "sparse normal Cholesky on CHOLMOD) and at most 25 linear solves "
        "(`--scaling-max-steps`): time per step is the measure; a run with fewer steps "
        "converged. Peak RSS is the whole `dynslam solve` process (reading and writing included).",
        "",
        *scaling_section(scaling, plot_dir / "scaling.png"),
        "",
        "## The sweep",
        "",
        "Configurations: `LINEAR/LM/tN` is Levenberg–Marquardt with a linear solver and backend "
        "(`schur` = sparse Schur, `snc` = sparse normal Cholesky; SuiteSparse's CHOLMOD or Eigen's "
        "SimplicialLDLT; `iterative_schur` with the Schur–Jacobi preconditioner), LM settings "
        "and N threads. LM settings: `dynslam` (the defaults: the remaining-χ² rule 0.01 with "
        "extrapolation, tolerances 1e-12, 500 steps, first damping auto), `gtsam_like` (first "
        "damping 1e-5, function tolerance 1e-5, 100 steps: GTSAM's released profile where Ceres "
        "has the knob), `ceres_defaults` (Ceres's own tolerances, 50 steps). `dogleg` is Powell's "
        "dogleg with sparse Schur and SuiteSparse, `dogleg_snc_eigen` and "
        "`dogleg_snc_suitesparse` with sparse normal Cholesky on Eigen or CHOLMOD; `monotonic` is "
        "LM with sparse normal Cholesky on CHOLMOD without the non-monotonic steps that the defaults take on "
        "graphs with kinematic edges; `default` is no option at all (`default/t2`: two threads). "
        "A solve that runs past the timeout is stopped and marked `timeout`.",
        *sweep_tables(runs),
        "",
    ]
    out.write_text("\n".join(text))
    print(f"wrote {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
