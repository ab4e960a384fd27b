"""A sweep's report: DIR/report.md, DIR/report/{summary,paired}.csv and box plots per metric."""
import csv
import math
import os

from . import _sweep_stats as st


def _number(x):
    """Four significant digits, so that 0.0021 and 1234 both read."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    return f"{x:.4g}"


def _interval(entry):
    if entry["n"] == 0:
        return "–"
    if entry["n"] < 2:
        return _number(entry["mean"])
    return f"{_number(entry['mean'])} [{_number(entry['ci_low'])}, {_number(entry['ci_high'])}]"


def _write_csv(path, rows):
    if not rows:
        open(path, "w").close()
        return
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def _box_plots(rows, folder):
    """One PNG per metric: a box per formulation and option set over every finished cell."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    done = [r for r in rows if r["status"] == "ok"]
    groups = sorted({(r["options"], r["formulation"]) for r in done})
    written = []
    for metric, label in st.METRICS:
        data = [[r[metric] for r in done if (r["options"], r["formulation"]) == g
                 and r[metric] is not None] for g in groups]
        if not any(data):
            continue
        figure, axes = plt.subplots(figsize=(1.2 + 0.9 * len(groups), 3.2))
        names = [f if o == "default" else f"{f}\n{o}" for o, f in groups]
        axes.boxplot(data, labels=names)
        axes.set_ylabel(label)
        axes.grid(axis="y", alpha=0.3)
        figure.tight_layout()
        path = os.path.join(folder, f"box_{metric}.png")
        figure.savefig(path, dpi=110)
        plt.close(figure)
        written.append(path)
    return written


def write(sweep_dir, rows):
    """Writes the report of `rows` (the results database's) under `sweep_dir`; returns the path
    of report.md."""
    folder = os.path.join(sweep_dir, "report")
    os.makedirs(folder, exist_ok=True)
    summary = st.summarise(rows)
    comparisons = st.paired(rows)
    _write_csv(os.path.join(folder, "summary.csv"), summary)
    _write_csv(os.path.join(folder, "paired.csv"), comparisons)
    plots = _box_plots(rows, folder)

    statuses = {}
    for row in rows:
        statuses[row["status"]] = statuses.get(row["status"], 0) + 1
    lines = ["# Sweep report", "",
             "Cells: " + ", ".join(f"{n} {s}" for s, n in sorted(statuses.items())) + ".", "",
             "Means over seeds with their 95 % confidence interval (Student's t) in brackets; "
             "errors are SPEC §5's mean relative errors.", ""]
    by_group = {}
    for entry in summary:
        key = (entry["options"], entry["scene"], entry["formulation"])
        by_group.setdefault(key, {})[entry["metric"]] = entry
    for options in sorted({k[0] for k in by_group}):
        groups = {k: v for k, v in by_group.items() if k[0] == options}
        measured = [(m, l) for m, l in st.METRICS + st.NEES
                    if any(m in entries for entries in groups.values())]
        lines += [f"## Option set `{options}`", "",
                  "| scene | formulation | seeds | " + " | ".join(l for _, l in measured) + " |",
                  "|---|---|---|" + "---|" * len(measured)]
        for (o, scene, formulation), entries in sorted(groups.items()):
            n = entries[st.METRICS[0][0]]["n"]
            cells = " | ".join(_interval(entries[m]) if m in entries else "–" for m, _ in measured)
            lines.append(f"| {scene} | {formulation} | {n} | {cells} |")
        lines.append("")
    lines += ["## Each formulation against wc", "",
              "Paired by scene and seed over every scene; median difference (formulation − wc); "
              "Wilcoxon signed-rank p, Holm-adjusted over the comparisons below; significant "
              "when the adjusted p < 0.05.", "",
              "| options | formulation | metric | pairs | median difference | p | p (Holm) | significant |",
              "|---|---|---|---|---|---|---|---|"]
    for c in comparisons:
        lines.append(f"| {c['options']} | {c['formulation']} | {c['metric']} | {c['pairs']} | "
                     f"{_number(c['median_difference'])} | {_number(c['p'])} | "
                     f"{_number(c['p_holm'])} | {'yes' if c['significant'] else 'no'} |")
    if plots:
        lines += ["", "## Box plots", ""]
        lines += [f"![{os.path.basename(p)}](report/{os.path.basename(p)})" for p in plots]
    path = os.path.join(sweep_dir, "report.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path
