"""A sweep's report: DIR/report.md, DIR/report/{summary,paired}.csv, box plots per metric and,
for a sweep over simulation sets, the sensitivity table and plots (_sweep_sensitivity)."""
import csv
import math
import os
import sys

from . import _html, _sweep_html
from . import _sweep_sensitivity as sensitivity
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
    """One PNG per metric: a box per formulation, simulation set and option set over every
    finished cell."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    done = [r for r in rows if r["status"] == "ok"]
    group_of = {id(r): (st.simulation(r), r["options"], r["formulation"]) for r in done}
    groups = sorted(set(group_of.values()))
    written = []
    for metric, label in st.METRICS:
        data = [[r[metric] for r in done if group_of[id(r)] == g and r[metric] is not None]
                for g in groups]
        if not any(data):
            continue
        figure, axes = plt.subplots(figsize=(1.2 + 0.9 * len(groups), 3.2))
        names = [f"{f}\n{st.setting_name(s, o)}".strip() for s, o, f in groups]
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
        key = ((entry["simulate"], entry["options"]), entry["scene"], entry["formulation"])
        by_group.setdefault(key, {})[entry["metric"]] = entry
    for simulate, options in sorted({k[0] for k in by_group}):
        groups = {k: v for k, v in by_group.items() if k[0] == (simulate, options)}
        measured = [(m, l) for m, l in st.METRICS + st.NEES
                    if any(m in entries for entries in groups.values())]
        title = f"Option set `{options}`"
        if simulate != "default":
            title = f"Simulation set `{simulate}`, option set `{options}`"
        lines += [f"## {title}", "",
                  "| scene | formulation | seeds | " + " | ".join(l for _, l in measured) + " |",
                  "|---|---|---|" + "---|" * len(measured)]
        for (_, scene, formulation), entries in sorted(groups.items()):
            n = entries[st.METRICS[0][0]]["n"]
            cells = " | ".join(_interval(entries[m]) if m in entries else "–" for m, _ in measured)
            lines.append(f"| {scene} | {formulation} | {n} | {cells} |")
        lines.append("")
    lines += ["## Each formulation against wc", "",
              "Paired by scene and seed over every scene; median difference (formulation − wc) "
              "with its distribution-free 95 % interval; Wilcoxon signed-rank p, Holm-adjusted "
              "over the comparisons below; significant when the adjusted p < 0.05.", "",
              "| simulation | options | formulation | metric | pairs | median difference | "
              "95 % interval | p | p (Holm) | significant |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for c in comparisons:
        lines.append(f"| {c['simulate']} | {c['options']} | {c['formulation']} | {c['metric']} | "
                     f"{c['pairs']} | {_number(c['median_difference'])} | "
                     f"[{_number(c['median_ci_low'])}, {_number(c['median_ci_high'])}] | "
                     f"{_number(c['p'])} | {_number(c['p_holm'])} | "
                     f"{'yes' if c['significant'] else 'no'} |")
    sensitivity_lines, sensitivity_plots = _sensitivity(sweep_dir, folder, comparisons)
    lines += sensitivity_lines
    if plots:
        lines += ["", "## Box plots", ""]
        lines += [f"![{os.path.basename(p)}](report/{os.path.basename(p)})" for p in plots]
    path = os.path.join(sweep_dir, "report.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    _write_html(sweep_dir, rows, "\n".join(lines), sensitivity_plots)
    return path


def _write_html(sweep_dir, rows, report_md, images):
    """DIR/report.html; without plotly.js, a warning line instead (report.md has it all)."""
    try:
        _html.write(os.path.join(sweep_dir, "report.html"),
                    _sweep_html.page(sweep_dir, rows, report_md, images))
    except (_html.ReportError, OSError) as error:
        print(f"warning: no report.html: {error}", file=sys.stderr)


def _sensitivity(sweep_dir, folder, comparisons):
    """The report's lines on simulation sets and its plots' paths: none for a sweep with one
    set."""
    if len({c["simulate"] for c in comparisons}) < 2:
        return [], []
    sets, defaults = sensitivity.read_settings(sweep_dir)
    lines = ["", "## Sensitivity to the simulator's settings", "",
             "Each formulation against wc per simulation set: median paired difference "
             "(formulation − wc; negative: better than wc), its 95 % interval and the "
             "Holm-adjusted p of the table above; bold where significant.", ""]
    lines += sensitivity.table(comparisons, sets, _number)
    plots = sensitivity.plots(comparisons, sets, defaults, folder)
    if plots:
        lines += ["", "Along each swept axis (the sets that change exactly those options, and "
                  "`default`):", ""]
        lines += [f"![{os.path.basename(p)}](report/{os.path.basename(p)})" for p in plots]
    return lines, plots
