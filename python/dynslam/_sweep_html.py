"""A sweep's DIR/report.html (docs/SWEEPS.md, "The report"): report.md's tables, a box plot per
metric (interactive), the sensitivity plots, and every cell with a link to its own page (its
report.html when the solve wrote one, `report = true` in an option set; else its summary.json).
"""
import base64
import html
import os

from . import _html
from . import _sweep_stats as st


def _box_figure(rows, metric, label):
    """A box per formulation, simulation set and option set over the finished cells."""
    groups = {}
    for row in rows:
        if row["status"] == "ok" and row.get(metric) is not None:
            name = f"{row['formulation']} {st.setting_name(st.simulation(row), row['options'])}"
            name = name.strip()
            groups.setdefault(name, []).append(row[metric])
    traces = [{"type": "box", "name": name, "y": values, "boxpoints": False}
              for name, values in sorted(groups.items())]
    layout = {"title": {"text": label, "font": {"size": 13}}, "height": 320, "showlegend": False,
              "margin": {"t": 40, "b": 80}}
    return {"data": traces, "layout": layout}


def _cell_link(sweep_dir, row):
    folder = row.get("cell_dir") or ""
    for name in ("report.html", "summary.json"):
        if os.path.isfile(os.path.join(sweep_dir, folder, name)):
            return f'<a href="{html.escape(os.path.join(folder, name))}">{html.escape(name)}</a>'
    return "–"


def _cells_table(sweep_dir, rows):
    head = ("scene", "seed", "simulate", "formulation", "options", "status", "steps",
            "final_cost")
    lines = ["<details><summary>Every cell (" + str(len(rows)) + ")</summary><table><thead><tr>"
             + "".join(f"<th>{h}</th>" for h in head) + "<th>page</th></tr></thead><tbody>"]
    for row in rows:
        cells = "".join(f"<td>{html.escape(str(row.get(h) if row.get(h) is not None else '–'))}"
                        f"</td>" for h in head)
        lines.append(f"<tr>{cells}<td>{_cell_link(sweep_dir, row)}</td></tr>")
    lines.append("</tbody></table></details>")
    return "\n".join(lines)


def _png(path):
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    return (f'<p><img alt="{html.escape(os.path.basename(path))}" style="max-width:100%" '
            f'src="data:image/png;base64,{data}"></p>')


def page(sweep_dir, rows, report_md, images):
    """The page's HTML: `report_md` (report.md's text, its image lines left out), a box plot per
    metric, `images` (PNG paths, embedded) and the cells."""
    text = "\n".join(line for line in report_md.splitlines()
                     if not line.startswith("![") and line != "## Box plots")
    plots = {f"box_{metric}": _box_figure(rows, metric, label) for metric, label in st.METRICS}
    plots = {k: v for k, v in plots.items() if v["data"]}
    sections = [_html.markdown_tables(text), "<h2>Box plots</h2>"]
    sections += [f'<div id="{plot_id}" class="plot"></div>' for plot_id in plots]
    sections += [_png(path) for path in images]
    sections += ["<h2>Cells</h2>", _cells_table(sweep_dir, rows)]
    return _html.page(f"Sweep report: {os.path.basename(os.path.abspath(sweep_dir))}", sections,
                      plots)
