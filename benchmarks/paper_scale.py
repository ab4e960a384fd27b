#!/usr/bin/python3
"""dynslam against GTSAM 4.2 at the paper's scale (issue 42), in one run on one machine.

Simulates each sequence at the paper's density (`dynslam simulate --density paper`, fixed seed),
builds every formulation, then for each graph runs, one after the other: GTSAM's `released`
profile (`dynslam solve --backend gtsam`), `dynslam solve` with its defaults, with `--tolerances
gtsam`, with `--threads N` (the cores this process may use; the sequences of --threads-check),
and with `--tolerances tight` (the best known optimum: the lowest final cost of all runs).
Without --gtsam it reports dynslam alone.

    benchmarks/paper_scale.py --gtsam build/gtsam/apps/dynslam [--sequences 0003 0005 0020]
        [--formulations wc oc_a …] [--out out/paper_scale] [--to-gtsam-cost-only]

With --to-gtsam-cost-only (for graphs whose solves to the optimum take hours, such as 0020's)
each graph gets GTSAM's `released` run and one dynslam defaults run, interrupted (SIGINT: it
stops after the step and writes its outputs) at its first accepted step at or below GTSAM's final
cost; OUT/table.md then has the time to GTSAM's cost only.

Writes OUT/runs.csv (every run: process wall time, peak resident memory, solve time, steps,
final cost, time to GTSAM's final cost) and OUT/table.md after every graph, and prints the table:
- GTSAM / dynslam to GTSAM's cost: GTSAM's solve time (its `time_s.total`) over dynslam's time
  to its first accepted step at or below GTSAM's final cost · (1 + 1e-6) (preprocessing plus
  the minimiser's time at that step, as benchmarks/gtsam_ratios.py measures it);
- whole process: the wall time of each command, reading the file to writing the outputs;
- χ² above the optimum: 2 × (final cost − the lowest final cost of the graph's runs), SPEC §1.5.
"""
import argparse
import csv
import datetime
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
from gtsam_ratios import commit, machine  # noqa: E402

FORMULATIONS = ["wc", "oc_a", "oc_b", "oc_c", "hy"]


def run(command, out_dir):
    """Runs `command` (writing into out_dir); returns (wall s, peak resident KiB, summary)."""
    os.makedirs(out_dir, exist_ok=True)
    start = time.perf_counter()
    with open(os.path.join(out_dir, "stdout.txt"), "w") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"failed ({os.waitstatus_to_exitcode(status)}): {' '.join(command)}; "
                 f"see {out_dir}/stdout.txt")
    with open(os.path.join(out_dir, "summary.json")) as f:
        return wall, usage.ru_maxrss, json.load(f)


def run_to_cost(command, out_dir, target):
    """Runs a dynslam solve and interrupts it once a step it prints (on stderr) is accepted at or
    below `target`; returns its summary (termination "interrupted", or its own stop before)."""
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "stderr.txt"), "w") as log:
        process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                   text=True)
        interrupted = False
        for line in process.stderr:
            log.write(line)
            words = line.split()
            if (not interrupted and words[:1] == ["step"] and "accepted" in words
                    and float(words[words.index("trial") + 1]) <= target):
                process.send_signal(signal.SIGINT)
                interrupted = True
        code = process.wait()
    if code not in (0, 130):
        sys.exit(f"failed ({code}): {' '.join(command)}; see {out_dir}/stderr.txt")
    with open(os.path.join(out_dir, "summary.json")) as f:
        return json.load(f)


def first_step_at(out_dir, target):
    """dynslam: the convergence.csv row of the first accepted step at or below target, or None."""
    with open(os.path.join(out_dir, "convergence.csv")) as f:
        for row in csv.DictReader(f):
            if row["accepted"] == "1" and float(row["trial_cost"]) <= target:
                return row
    return None


def time_to_cost(summary, row):
    """dynslam: preprocessing + minimiser time at `row` (first_step_at's), None without one."""
    return summary["time_s"]["preprocessing"] + float(row["time_s"]) if row else None


def prepare(cli, sequence, seed, formulations, out):
    """The front end of `sequence` at the paper's density and its built graphs."""
    scene = out / sequence
    scene.mkdir(parents=True, exist_ok=True)
    prefix = scene / "frontend"
    if not (scene / "frontend.gt.txt").exists():
        subprocess.run([cli, "simulate", "--seq", sequence, "--density", "paper", "--seed",
                        str(seed), "--out", str(prefix)], check=True, stdout=subprocess.DEVNULL)
    graphs = {}
    for f in formulations:
        graphs[f] = scene / f"{f}.g2o"
        if not graphs[f].exists():
            subprocess.run([cli, "build", f"{prefix}.g2o", "--formulation", f, "--gt",
                            f"{prefix}.gt.txt", "--out", str(graphs[f])], check=True,
                           stdout=subprocess.DEVNULL)
    return graphs


def gtsam_released(args, formulation, graph, out):
    """GTSAM's `released` run of one graph (the GTSAM backend, docs/GTSAM_BACKEND.md) as a row."""
    d = out / "gtsam_released"
    wall, peak, s = run([args.gtsam, "solve", str(graph), "--backend", "gtsam:released", "--out",
                         str(d)], str(d))
    return {"run": "gtsam_released", "wall_s": wall, "peak_kib": peak,
            "solve_s": s["time_s"]["total"], "steps": s["iterations"],
            "final_cost": s["final_cost"], "to_gtsam_cost_s": s["time_s"]["total"]}


def runs_to_gtsam_cost(args, sequence, formulation, graph, out):
    """--to-gtsam-cost-only: GTSAM's run, then dynslam's defaults up to GTSAM's final cost."""
    g = gtsam_released(args, formulation, graph, out)
    target = g["final_cost"] * (1 + 1e-6)
    d = out / "defaults_to_gtsam_cost"
    s = run_to_cost([args.dynslam, "solve", str(graph), "--out", str(d)], str(d), target)
    reached = first_step_at(str(d), target)
    rows = [g, {"run": "defaults_to_gtsam_cost", "steps": int(reached["step"]) if reached else None,
                "final_cost": s["final_cost"], "variables": s["variables"]["total"],
                "to_gtsam_cost_s": time_to_cost(s, reached)}]
    for r in rows:
        r.update(sequence=sequence, formulation=formulation)
    return rows


def runs_of_graph(args, sequence, formulation, graph, out):
    """Every run of one graph, in the order they ran."""
    rows = []
    target = None
    if args.gtsam:
        rows.append(gtsam_released(args, formulation, graph, out))
        target = rows[0]["final_cost"] * (1 + 1e-6)
    runs = [("defaults", []), ("tolerances_gtsam", ["--tolerances", "gtsam"])]
    if sequence in args.threads_check:
        runs.append(("threads_all", ["--threads", str(len(os.sched_getaffinity(0)))]))
    if not args.no_tight:
        runs.append(("tight", ["--tolerances", "tight"]))
    for name, flags in runs:
        d = out / name
        wall, peak, s = run([args.dynslam, "solve", str(graph), "--out", str(d), *flags], str(d))
        reached = first_step_at(str(d), target) if target else None
        rows.append({"run": name, "wall_s": wall, "peak_kib": peak,
                     "solve_s": s["time_s"]["total"], "steps": s["steps"],
                     "final_cost": s["final_cost"], "variables": s["variables"]["total"],
                     "to_gtsam_cost_s": time_to_cost(s, reached)})
    optimum = min(r["final_cost"] for r in rows)
    for r in rows:
        r.update(sequence=sequence, formulation=formulation,
                 chi2_above_optimum=2 * (r["final_cost"] - optimum))
    return rows


def ratio(a, b):
    return f"{a / b:.2f}×" if a and b else "–"


def table_to_gtsam_cost(rows):
    lines = ["| graph | variables | GTSAM released: iterations, solve s | dynslam defaults: steps "
             "and s to GTSAM's cost | to GTSAM's cost, GTSAM / dynslam |", "|---|---|---|---|---|"]
    by = {(r["sequence"], r["formulation"], r["run"]): r for r in rows}
    graphs = sorted({(r["sequence"], r["formulation"]) for r in rows},
                    key=lambda g: (g[0], FORMULATIONS.index(g[1])))
    for sequence, formulation in graphs:
        g = by[(sequence, formulation, "gtsam_released")]
        d = by[(sequence, formulation, "defaults_to_gtsam_cost")]
        to_cost = (f"{d['steps']}, {d['to_gtsam_cost_s']:.1f}" if d["to_gtsam_cost_s"]
                   else "not reached")
        lines.append(f"| {sequence} {formulation} | {d['variables']} | {g['steps']}, "
                     f"{g['solve_s']:.1f} | {to_cost} | "
                     f"{ratio(g['solve_s'], d['to_gtsam_cost_s'])} |")
    return lines


def table(rows):
    lines = ["| graph | variables | GTSAM released: iterations, process s, χ² above optimum | "
             "dynslam defaults: steps, process s, χ² above optimum | to GTSAM's cost, GTSAM / "
             "dynslam | whole process, GTSAM / dynslam | `--tolerances gtsam`: steps, process s, "
             "GTSAM / dynslam | 1 thread / all cores, process | peak memory per variable |",
             "|---|---|---|---|---|---|---|---|---|"]
    graphs = sorted({(r["sequence"], r["formulation"]) for r in rows},
                    key=lambda g: (g[0], FORMULATIONS.index(g[1])))
    for sequence, formulation in graphs:
        by = {r["run"]: r for r in rows
              if (r["sequence"], r["formulation"]) == (sequence, formulation)}
        d, g, t, many = by["defaults"], by.get("gtsam_released"), by["tolerances_gtsam"], \
            by.get("threads_all")
        gtsam = (f"{g['steps']}, {g['wall_s']:.1f}, {g['chi2_above_optimum']:.3f}" if g else "–")
        lines.append(
            f"| {sequence} {formulation} | {d['variables']} | {gtsam} | {d['steps']}, "
            f"{d['wall_s']:.1f}, {d['chi2_above_optimum']:.3f} | "
            f"{ratio(g and g['solve_s'], d['to_gtsam_cost_s'])} | "
            f"{ratio(g and g['wall_s'], d['wall_s'])} | {t['steps']}, {t['wall_s']:.1f}, "
            f"{ratio(g and g['wall_s'], t['wall_s'])} | "
            f"{ratio(d['wall_s'], many and many['wall_s'])} | "
            f"{d['peak_kib'] / d['variables']:.2f} KiB |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sequences", nargs="+", default=["0003", "0005", "0020"])
    parser.add_argument("--formulations", nargs="+", default=FORMULATIONS, choices=FORMULATIONS)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--gtsam", help="a dynslam built with the GTSAM backend "
                                        "(scripts/build_gtsam: build/gtsam/apps/dynslam)")
    parser.add_argument("--dynslam", default=str(ROOT / "build/release/apps/dynslam"))
    parser.add_argument("--threads-check", nargs="*", default=["0020"],
                        help="sequences also solved with --threads N, N the cores this process "
                             "may use (the default is one thread)")
    parser.add_argument("--no-tight", action="store_true",
                        help="no --tolerances tight solve (the optimum is then the best of the rest)")
    parser.add_argument("--to-gtsam-cost-only", action="store_true",
                        help="GTSAM's run and dynslam's defaults up to GTSAM's cost, nothing else "
                             "(needs --gtsam)")
    parser.add_argument("--out", default=str(ROOT / "out/paper_scale"))
    args = parser.parse_args()
    if args.to_gtsam_cost_only and not args.gtsam:
        parser.error("--to-gtsam-cost-only needs --gtsam")
    runs_of = runs_to_gtsam_cost if args.to_gtsam_cost_only else runs_of_graph
    out = pathlib.Path(args.out)
    rows = []
    for sequence in args.sequences:
        graphs = prepare(args.dynslam, sequence, args.seed, args.formulations, out)
        for formulation, graph in graphs.items():
            rows += runs_of(args, sequence, formulation, graph,
                            out / sequence / "runs" / formulation)
            # after every graph: a long run stopped keeps what it measured
            write(out, rows, table_to_gtsam_cost if args.to_gtsam_cost_only else table)
            print(f"[paper_scale] {sequence} {formulation} done", file=sys.stderr, flush=True)
    print((out / "table.md").read_text(), end="")


def write(out, rows, make_table):
    """OUT/runs.csv, OUT/table.md and OUT/runs.json (command, date, commit, machine)."""
    fields = ["sequence", "formulation", "run", "variables", "steps", "final_cost",
              "chi2_above_optimum", "solve_s", "to_gtsam_cost_s", "wall_s", "peak_kib"]
    with open(out / "runs.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    (out / "table.md").write_text("\n".join(make_table(rows)) + "\n")
    with open(out / "runs.json", "w") as f:
        json.dump({"command": "benchmarks/paper_scale.py " + " ".join(sys.argv[1:]),
                   "date": datetime.date.today().isoformat(), "commit": commit(),
                   "machine": machine()}, f, indent=1)


if __name__ == "__main__":
    main()
