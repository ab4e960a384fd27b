"""Self-contained HTML reports (docs/GUIDE.md, "Reports"): one file with plotly.js embedded, no
network access (a Content-Security-Policy forbids any), opened from file:// in any browser.

- `compare_page(folders, labels, gt, title, tables_md)`: a compare's (or one solve's) scene in 3D
  against the ground truth, per-frame errors (with ±3σ bands where covariances.csv exists),
  convergence, and Tables I–III;
- `sweep_page(...)` (in _sweep_html): a sweep's statistics, box plots and links to its cells.

Plain Python and the standard library; plotly.js comes from Debian's python3-plotly.
"""
import csv
import html
import json
import math
import os
import re

PLOTLY_JS = ("/usr/share/python3-plotly/plotly.js",)
POSE = ("tx", "ty", "tz", "qx", "qy", "qz", "qw")
# Static points drawn at most: the page stays small for whole sequences (docs/GUIDE.md).
MAX_STATIC_POINTS = 4000
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
           "#17becf", "#bcbd22", "#7f7f7f"]


class ReportError(Exception):
    """A report that cannot be written: 'FILE[:LINE]: problem'."""


def plotly_js():
    """plotly.js's text: Debian's copy (python3-plotly), else the Python package's."""
    for path in PLOTLY_JS:
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                return f.read()
    try:
        from plotly.offline import get_plotlyjs
    except ImportError:
        raise ReportError("no plotly.js: install Debian's python3-plotly") from None
    return get_plotlyjs()


def _rows(path, needed):
    """A CSV file's rows as dicts; every column of `needed` must be there."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
            header = set(rows[0]) if rows else set()
    except OSError as error:
        raise ReportError(f"{path}: cannot read the file: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise ReportError(f"{path}: not a text file") from None
    missing = set(needed) - header
    if rows and missing:
        raise ReportError(f"{path}:1: no column {', '.join(sorted(missing))}")
    return rows


def _float(text, path, line):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise ReportError(f"{path}:{line}: '{text}' is not a number") from None


def read_poses(path, keys):
    """{key: (x, y, z)} of cameras.csv (keys ('frame',)) or object_poses.csv ('object',
    'frame'); a key of one column is that column's integer."""
    out = {}
    for line, row in enumerate(_rows(path, keys + POSE), start=2):
        key = tuple(int(_float(row[k], path, line)) for k in keys)
        out[key[0] if len(key) == 1 else key] = tuple(_float(row[c], path, line)
                                                     for c in ("tx", "ty", "tz"))
    return out


def read_ground_truth(path):
    """(cameras {frame: xyz}, objects {(object, frame): xyz}) of a SPEC §2 file."""
    cameras, objects = {}, {}
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as error:
        raise ReportError(f"{path}: cannot read the file: {error}") from None
    for line, text in enumerate(lines, start=1):
        fields = text.split("#", 1)[0].split()
        if not fields:
            continue
        if fields[0] == "CAMERA" and len(fields) == 9:
            cameras[int(fields[1])] = tuple(_float(x, path, line) for x in fields[2:5])
        elif fields[0] == "OBJECT" and len(fields) == 10:
            objects[(int(fields[2]), int(fields[1]))] = tuple(_float(x, path, line)
                                                              for x in fields[3:6])
        else:
            raise ReportError(f"{path}:{line}: not a CAMERA or OBJECT record (SPEC §2)")
    return cameras, objects


def read_static_points(path):
    """The static points of a solution.g2o (VERTEX_TRACKXYZ with LABEL_STATIC_POINT), every
    n-th one so that at most MAX_STATIC_POINTS remain."""
    points, static = {}, set()
    try:
        with open(path, encoding="utf-8") as f:
            for text in f:
                fields = text.split()
                if fields[:1] == ["VERTEX_TRACKXYZ"] and len(fields) == 5:
                    points[fields[1]] = tuple(float(x) for x in fields[2:5])
                elif fields[:1] == ["LABEL_STATIC_POINT"] and len(fields) >= 2:
                    static.add(fields[1])
    except (OSError, UnicodeDecodeError, ValueError) as error:
        raise ReportError(f"{path}: cannot read the points: {error}") from None
    chosen = [points[i] for i in sorted(static & set(points), key=int)]
    step = max(1, math.ceil(len(chosen) / MAX_STATIC_POINTS))
    return chosen[::step]


def camera_sigmas(folder):
    """{frame: 3σ of the camera position (m)} from covariances.csv and solution.g2o's camera
    labels: 3·√trace(Σ_ρρ), the translation block of the 6×6 [ω; ρ] covariance (its trace does
    not depend on the frame it is expressed in); {} when the solve wrote no covariances."""
    path = os.path.join(folder, "covariances.csv")
    if not os.path.isfile(path):
        return {}
    frame_of = {}
    with open(os.path.join(folder, "solution.g2o"), encoding="utf-8") as f:
        for text in f:
            fields = text.split()
            if fields[:1] == ["LABEL_CAMERA"] and len(fields) == 3:
                frame_of[fields[1]] = int(fields[2])
    sigmas = {}
    with open(path, newline="", encoding="utf-8") as f:
        for line, row in enumerate(csv.reader(f), start=1):
            if line == 1 or len(row) != 24 or row[0] not in frame_of:
                continue
            upper = [_float(x, path, line) for x in row[3:]]
            # Diagonal of the upper triangle, row by row: indices 0, 6, 11, 15, 18, 20.
            trace_rho = upper[15] + upper[18] + upper[20]
            sigmas[frame_of[row[0]]] = 3 * math.sqrt(max(trace_rho, 0.0))
    return sigmas


def _line(xyz_by_key, keys):
    """x, y, z lists over `keys` in order, None where a key is missing (a break in the line)."""
    xs, ys, zs = [], [], []
    previous = None
    for key in keys:
        if previous is not None and key != previous + 1:
            xs.append(None), ys.append(None), zs.append(None)
        x, y, z = xyz_by_key[key]
        xs.append(round(x, 4)), ys.append(round(y, 4)), zs.append(round(z, 4))
        previous = key
    return xs, ys, zs


def _trace3d(xyz_by_frame, name, colour, group, obj, dash="solid", width=3):
    xs, ys, zs = _line(xyz_by_frame, sorted(xyz_by_frame))
    # The camera's y points down (SPEC §0, KITTI): the plot's up is −y.
    return {"type": "scatter3d", "mode": "lines", "name": name, "x": xs, "y": zs,
            "z": [None if y is None else -y for y in ys],
            "line": {"color": colour, "width": width, "dash": dash},
            "meta": {"group": group, "object": obj}}


def _by_object(objects):
    grouped = {}
    for (obj, frame), xyz in objects.items():
        grouped.setdefault(obj, {})[frame] = xyz
    return grouped


def scene_figure(runs, gt, static_points):
    """The 3D scene: cameras and object paths per run (label, cameras, objects) and of the
    ground truth; static points of the first run."""
    traces = []
    if static_points:
        traces.append({"type": "scatter3d", "mode": "markers", "name": "static points",
                        "x": [round(p[0], 3) for p in static_points],
                        "y": [round(p[2], 3) for p in static_points],
                        "z": [round(-p[1], 3) for p in static_points],
                        "marker": {"size": 1.5, "color": "#999999"},
                        "meta": {"group": "static points", "object": "camera"}})
    if gt is not None:
        cameras, objects = gt
        traces.append(_trace3d(cameras, "ground truth: camera", "black", "ground truth",
                               "camera", "dash"))
        for obj, path in sorted(_by_object(objects).items()):
            traces.append(_trace3d(path, f"ground truth: object {obj}", "black",
                                   "ground truth", str(obj), "dash"))
    for index, (label, cameras, objects) in enumerate(runs):
        colour = COLOURS[index % len(COLOURS)]
        traces.append(_trace3d(cameras, f"{label}: camera", colour, label, "camera"))
        for obj, path in sorted(_by_object(objects).items()):
            traces.append(_trace3d(path, f"{label}: object {obj}", colour, label, str(obj),
                                   width=4))
    layout = {"height": 640, "margin": {"l": 0, "r": 0, "t": 30, "b": 0},
              "scene": {"aspectmode": "data", "xaxis": {"title": "x (m)"},
                        "yaxis": {"title": "z, forward (m)"}, "zaxis": {"title": "up (m)"}},
              "legend": {"font": {"size": 10}}}
    return {"data": traces, "layout": layout}


def position_figure(runs, gt_cameras, sigmas):
    """Each run's camera position error against the ground truth per frame, |t − t_gt| (the
    world is the first camera, SPEC §2, so no alignment), with its 3σ where covariances exist."""
    traces = []
    for index, (label, cameras, _) in enumerate(runs):
        frames = sorted(k for k in cameras if k in gt_cameras)
        colour = COLOURS[index % len(COLOURS)]
        traces.append({"type": "scatter", "mode": "lines", "name": label, "x": frames,
                       "y": [round(math.dist(cameras[k], gt_cameras[k]), 6) for k in frames],
                       "line": {"color": colour}})
        if label in sigmas:
            band = sigmas[label]
            frames = sorted(band)
            traces.append({"type": "scatter", "mode": "lines", "name": f"{label}: 3σ",
                           "x": frames, "y": [round(band[k], 6) for k in frames],
                           "line": {"color": colour, "dash": "dot", "width": 1}})
    layout = {"title": {"text": "Camera position error per frame (absolute)", "font": {"size": 14}},
              "height": 340, "xaxis": {"title": "frame"},
              "yaxis": {"title": "|t − t_gt| (m)"}, "margin": {"t": 40}}
    return {"data": traces, "layout": layout}


def errors_figure(folders, labels, quantity, title):
    """Per-frame errors of `quantity` (errors.csv: camera, object_motion, object_pose): rotation
    and translation, a line per run (and per object)."""
    traces = []
    for index, (folder, label) in enumerate(zip(folders, labels)):
        path = os.path.join(folder, "errors.csv")
        if not os.path.isfile(path):
            continue
        series = {}
        for line, row in enumerate(_rows(path, ("quantity", "object", "frame", "rot_deg",
                                                "trans_m")), start=2):
            if row["quantity"] == quantity:
                series.setdefault(row["object"], []).append(
                    (int(row["frame"]), _float(row["rot_deg"], path, line),
                     _float(row["trans_m"], path, line)))
        colour = COLOURS[index % len(COLOURS)]
        for obj, points in sorted(series.items()):
            points.sort()
            name = label if obj == "-1" else f"{label}: object {obj}"
            frames = [p[0] for p in points]
            for axis, column in (("y", 1), ("y2", 2)):
                traces.append({"type": "scatter", "mode": "lines+markers", "name": name,
                               "x": frames, "y": [round(p[column], 6) for p in points],
                               "yaxis": axis, "legendgroup": name, "showlegend": axis == "y",
                               "line": {"color": colour, "width": 1.5},
                               "marker": {"size": 3}})
    layout = {"title": {"text": title, "font": {"size": 14}}, "height": 420,
              "xaxis": {"title": "frame", "anchor": "y2"},
              "yaxis": {"title": "rotation (°)", "domain": [0.55, 1]},
              "yaxis2": {"title": "translation (m)", "domain": [0, 0.45], "anchor": "x"},
              "margin": {"t": 40}}
    return {"data": traces, "layout": layout}


def read_convergence(folder):
    """[(step, time_s, cost after the step)] of a solve's convergence.csv (the trial cost of an
    accepted step, else the cost it started from); [] when there is none."""
    path = os.path.join(folder, "convergence.csv")
    if not os.path.isfile(path):
        return []
    rows = _rows(path, ("step", "cost", "trial_cost", "accepted", "time_s"))
    return [(int(r["step"]), _float(r["time_s"], path, line),
             _float(r["trial_cost"] if r["accepted"].strip() == "1" else r["cost"], path, line))
            for line, r in enumerate(rows, start=2)]


def convergence_figure(folders, labels):
    """Cost above the final one against step and against time (log scale), a line per run."""
    traces = []
    for index, (folder, label) in enumerate(zip(folders, labels)):
        rows = read_convergence(folder)
        if not rows:
            continue
        final = min(cost for _, _, cost in rows)
        above = [max(cost - final, 1e-12) for _, _, cost in rows]
        colour = COLOURS[index % len(COLOURS)]
        for axis, x in (("x", [r[0] for r in rows]), ("x2", [round(r[1], 4) for r in rows])):
            traces.append({"type": "scatter", "mode": "lines+markers", "name": label, "x": x,
                           "y": above, "xaxis": axis, "legendgroup": label,
                           "showlegend": axis == "x", "line": {"color": colour}})
    layout = {"height": 400, "yaxis": {"type": "log", "title": "cost above the final"},
              "xaxis": {"title": "step", "domain": [0, 0.47]},
              "xaxis2": {"title": "time (s)", "domain": [0.53, 1], "anchor": "y"},
              "margin": {"t": 20}}
    return {"data": traces, "layout": layout}


def _inline(text):
    """Markdown's **bold** and `code` in a table cell or paragraph, the rest escaped."""
    escaped = html.escape(text)
    escaped = re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", escaped)
    return re.sub(r"`(.+?)`", r"<code>\1</code>", escaped)


def markdown_tables(text):
    """Markdown headings and pipe tables (as tables.md and report.md write them) as HTML."""
    out, table = [], []

    def flush():
        if table:
            head, body = table[0], table[2:]
            cells = lambda row, tag: "".join(f"<{tag}>{_inline(c)}</{tag}>" for c in row)
            out.append("<table><thead><tr>" + cells(head, "th") + "</tr></thead><tbody>"
                       + "".join(f"<tr>{cells(r, 'td')}</tr>" for r in body)
                       + "</tbody></table>")
            table.clear()

    for line in text.splitlines():
        if line.startswith("|"):
            table.append([c.strip() for c in line.strip().strip("|").split("|")])
            continue
        flush()
        if line.startswith("#"):
            level = min(len(line) - len(line.lstrip("#")) + 1, 4)
            out.append(f"<h{level}>{_inline(line.lstrip('#').strip())}</h{level}>")
        elif line.strip():
            out.append(f"<p>{_inline(line)}</p>")
    flush()
    return "\n".join(out)


# Every script error, console error or blocked request is listed on the page itself
# (#dynslam-errors), where a test or a reader sees it.
ERRORS_JS = """
window.dynslamErrors = [];
function dynslamError(text) {
  window.dynslamErrors.push(text);
  const box = document.getElementById('dynslam-errors');
  if (box) box.textContent = window.dynslamErrors.join('; ');
}
window.addEventListener('error', e => dynslamError(String(e.message)));
window.addEventListener('unhandledrejection', e => dynslamError(String(e.reason)));
document.addEventListener('securitypolicyviolation', e => dynslamError('blocked: ' + e.blockedURI));
const dynslamConsoleError = console.error;
console.error = (...args) => { dynslamError(args.join(' ')); dynslamConsoleError(...args); };
"""
# Draws every figure; body's data-plots is how many there are, data-drawn how many were drawn.
DRAW_JS = """
document.body.dataset.plots = Object.keys(dynslamFigures).length;
Promise.all(Object.entries(dynslamFigures).map(([id, f]) =>
  Plotly.newPlot(id, f.data, f.layout, {responsive: true, displaylogo: false}).then(() => {
    if (document.getElementById(id + '-toggles')) dynslamToggles(id);
    return 1;
  }).catch(e => { dynslamError(String(e)); return 0; })
)).then(done => { document.body.dataset.drawn = done.reduce((a, b) => a + b, 0); });
"""
TOGGLES_JS = """
function dynslamToggles(id) {
  const box = document.getElementById(id + '-toggles');
  const plot = document.getElementById(id);
  const update = () => {
    const on = new Set([...box.querySelectorAll('input:checked')].map(i => i.value));
    const visible = plot.data.map(t => on.has('g:' + t.meta.group) && on.has('o:' + t.meta.object));
    Plotly.restyle(plot, {visible: visible});
  };
  box.addEventListener('change', update);
}
"""


def toggles(plot_id, figure):
    """Checkboxes per run (and ground truth) and per object for the 3D scene."""
    groups = list(dict.fromkeys(t["meta"]["group"] for t in figure["data"]))
    objects = list(dict.fromkeys(t["meta"]["object"] for t in figure["data"]))
    box = lambda prefix, value, text: (f'<label><input type="checkbox" value="{prefix}:'
                                       f'{html.escape(value)}" checked> {html.escape(text)}'
                                       f"</label>")
    return (f'<div id="{plot_id}-toggles" class="toggles"><b>show:</b> '
            + " ".join(box("g", g, g) for g in groups) + " &nbsp; <b>objects:</b> "
            + " ".join(box("o", o, o if o == "camera" else f"object {o}") for o in objects)
            + "</div>")


CSS = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: right; }
th { background: #f3f3f3; }
.toggles { font-size: 13px; margin: 0.3em 0; }
.toggles label { margin-right: 0.8em; white-space: nowrap; }
.plot { width: 100%; }
#dynslam-errors { color: #b00; }
"""


def page(title, sections, plots):
    """A whole HTML document: `sections` (HTML strings, in order) and `plots` ({div id: figure},
    drawn by Plotly.newPlot once the page has loaded). Any script error is shown on the page (a
    test reads it) and no resource can be fetched (Content-Security-Policy)."""
    policy = ("default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
              "img-src data:; font-src data:")
    figures = json.dumps(plots, separators=(",", ":"), allow_nan=False)
    return "\n".join([
        "<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
        f'<meta http-equiv="Content-Security-Policy" content="{policy}">',
        f"<title>{html.escape(title)}</title><style>{CSS}</style>",
        f"<script>{ERRORS_JS}</script>",
        f"<script>{plotly_js()}</script>", "</head><body>",
        f"<h1>{html.escape(title)}</h1>", '<div id="dynslam-errors"></div>', *sections,
        f"<script>{TOGGLES_JS}\nconst dynslamFigures = {figures};\n{DRAW_JS}</script>",
        "</body></html>"])


def _finite(figure):
    """The figure with NaN and ±∞ numbers as None (JSON has neither)."""
    def clean(value):
        if isinstance(value, float) and not math.isfinite(value):
            return None
        if isinstance(value, list):
            return [clean(v) for v in value]
        if isinstance(value, dict):
            return {k: clean(v) for k, v in value.items()}
        return value
    return clean(figure)


def compare_page(folders, labels, gt_path=None, title="", tables_md=None):
    """The HTML of a compare (several solve folders) or of one solve (one folder)."""
    runs = [(label, read_poses(os.path.join(f, "cameras.csv"), ("frame",)),
             read_poses(os.path.join(f, "object_poses.csv"), ("object", "frame")))
            for f, label in zip(folders, labels)]
    gt = read_ground_truth(gt_path) if gt_path else None
    static = read_static_points(os.path.join(folders[0], "solution.g2o"))
    plots = {"scene": scene_figure(runs, gt, static)}
    sections = ["<h2>The scene</h2>", "<p>Drag to turn, scroll to zoom; dashed: ground truth. "
                "Up is the camera's −y.</p>", toggles("scene", plots["scene"]),
                '<div id="scene" class="plot"></div>']
    if tables_md:
        sections += ["<h2>Tables</h2>", markdown_tables(tables_md)]
    if gt is not None:
        sigmas = {label: camera_sigmas(f) for f, label in zip(folders, labels)}
        plots["position"] = position_figure(runs, gt[0], {k: v for k, v in sigmas.items() if v})
        sections += ["<h2>Errors per frame</h2>", '<div id="position" class="plot"></div>']
        if any(sigmas.values()):
            sections.append("<p>Dotted: 3·√trace of the camera position's marginal covariance "
                            "(covariances.csv).</p>")
        for quantity, name in (("camera", "Camera relative pose error per frame"),
                               ("object_motion", "Object motion error per frame"),
                               ("object_pose", "Object pose error per frame")):
            plots[quantity] = errors_figure(folders, labels, quantity, name)
            sections.append(f'<div id="{quantity}" class="plot"></div>')
    plots["convergence"] = convergence_figure(folders, labels)
    sections += ["<h2>Convergence</h2>", '<div id="convergence" class="plot"></div>']
    return page(title or "dynslam report", sections,
                {k: _finite(v) for k, v in plots.items()})


def write(path, text):
    """Writes the page whole under a temporary name, then renames it."""
    temporary = f"{path}.tmp-{os.getpid()}"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(temporary, path)
