"""How a sweep's answer depends on the simulator's settings (docs/SWEEPS.md, "Simulation sets"):
each formulation against wc per simulation set in one table, and along each swept axis a plot of
the paired difference with its interval against the setting's value.

An axis is the set of simulator options that a simulation set changes from the simulator's
defaults (`pixel_sigma`, or `pixel_sigma` and `disparity_sigma` together); the sets that change
exactly those options, and the set `default`, are its points, at the value of its first option.
"""
import json
import math
import os

# The SPEC §5 errors the sensitivity report compares: (column, short label).
METRICS = [
    ("object_motion_mean_rot_deg", "motion E_r (°)"),
    ("object_motion_mean_trans_m", "motion E_t (m)"),
    ("object_pose_mean_rot_deg", "pose E_r (°)"),
    ("object_pose_mean_trans_m", "pose E_t (m)"),
    ("camera_mean_rot_deg", "camera E_r (°)"),
    ("camera_mean_trans_m", "camera E_t (m)"),
]
SETTINGS_FILE = "simulate_sets.json"


def write_settings(sweep_dir, settings, defaults):
    """DIR/simulate_sets.json: each simulation set's options as the sweep file gives them and the
    simulator's defaults of those options, for the report (which may run later, from DIR)."""
    used = {key for options in settings.values() for key in options}
    with open(os.path.join(sweep_dir, SETTINGS_FILE), "w") as f:
        json.dump({"sets": settings, "defaults": {k: defaults.get(k) for k in sorted(used)}}, f,
                  indent=1, sort_keys=True)


def read_settings(sweep_dir):
    """(sets, defaults) written by write_settings, or ({}, {}) for a sweep without them."""
    try:
        with open(os.path.join(sweep_dir, SETTINGS_FILE)) as f:
            saved = json.load(f)
    except (OSError, ValueError):
        return {}, {}
    return saved.get("sets", {}), saved.get("defaults", {})


def _number(value):
    """A setting as a number for an axis: booleans and on/off as 0/1, numbers as they are."""
    if isinstance(value, bool):
        return float(value)
    text = str(value).lower()
    if text in ("on", "true"):
        return 1.0
    if text in ("off", "false"):
        return 0.0
    try:
        return float(text)
    except ValueError:
        return math.nan


def _changed(options, defaults):
    """The options of a set whose value differs from the simulator's default."""
    return {k: v for k, v in options.items() if _number(v) != _number(defaults.get(k))}


def axes(sets, defaults):
    """{axis name: [(x, set name), …] sorted by x}: the axes with at least two points."""
    found = {}
    for name, options in sets.items():
        changed = _changed(options, defaults)
        if changed:
            found.setdefault(tuple(sorted(changed)), []).append((changed, name))
    result = {}
    for keys, members in found.items():
        points = [(_number(changed[keys[0]]), name) for changed, name in members]
        if "default" in sets and not _changed(sets["default"], defaults):
            points.append((_number(defaults.get(keys[0])), "default"))
        points = sorted(p for p in points if not math.isnan(p[0]))
        if len(points) >= 2:
            result[" + ".join(keys)] = points
    return result


def _cell(comparison, number):
    if comparison is None or comparison["pairs"] == 0:
        return "–"
    text = (f"{number(comparison['median_difference'])} "
            f"[{number(comparison['median_ci_low'])}, {number(comparison['median_ci_high'])}] "
            f"p={number(comparison['p_holm'])}")
    return f"**{text}**" if comparison["significant"] else text


def table(comparisons, sets, number):
    """Markdown lines: per option set, simulation set and formulation, each metric's median
    paired difference against wc, its 95 % interval and Holm-adjusted p (bold: significant)."""
    by_key = {(c["options"], c["simulate"], c["formulation"], c["metric"]): c for c in comparisons}
    lines = ["| options | simulation set | settings | formulation | "
             + " | ".join(label for _, label in METRICS) + " |",
             "|---|---|---|---|" + "---|" * len(METRICS)]
    for options, simulate, formulation in sorted({k[:3] for k in by_key}):
        settings = ", ".join(f"{k} = {v}" for k, v in sorted(sets.get(simulate, {}).items()))
        cells = " | ".join(_cell(by_key.get((options, simulate, formulation, m)), number)
                           for m, _ in METRICS)
        lines.append(f"| {options} | {simulate} | {settings or 'the defaults'} | {formulation} | "
                     f"{cells} |")
    return lines


def plots(comparisons, sets, defaults, folder):
    """One PNG per axis and option set: a panel per metric, the median paired difference
    (formulation − wc) with its 95 % interval against the setting, a line per formulation."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    by_key = {(c["options"], c["simulate"], c["formulation"], c["metric"]): c for c in comparisons}
    formulations = sorted({c["formulation"] for c in comparisons})
    written = []
    for options in sorted({c["options"] for c in comparisons}):
        for axis, points in axes(sets, defaults).items():
            figure, panels = plt.subplots(2, 3, figsize=(12, 6.4), sharex=True)
            for panel, (metric, label) in zip(panels.flat, METRICS):
                for offset, formulation in enumerate(formulations):
                    xs, ys, lows, highs = [], [], [], []
                    for x, name in points:
                        c = by_key.get((options, name, formulation, metric))
                        if c is None or c["pairs"] == 0:
                            continue
                        xs.append(x)
                        ys.append(c["median_difference"])
                        lows.append(c["median_difference"] - c["median_ci_low"])
                        highs.append(c["median_ci_high"] - c["median_difference"])
                    if xs:
                        panel.errorbar(xs, ys, yerr=[lows, highs], marker="o", capsize=3,
                                       label=formulation, alpha=0.85)
                panel.axhline(0, color="black", linewidth=0.8)
                panel.set_title(f"{label} − wc", fontsize=10)
                panel.grid(alpha=0.3)
            xs = [x for x, _ in points]
            for panel in panels.flat:
                if min(xs) > 0 and max(xs) >= 4 * min(xs):  # values that double: a log axis
                    panel.set_xscale("log", base=2)
            for panel in panels[-1]:
                panel.set_xlabel(axis)
            panels.flat[0].legend(fontsize=8)
            figure.suptitle(f"Paired difference against wc (median, 95 % interval), option set "
                            f"{options}", fontsize=11)
            figure.tight_layout()
            suffix = "" if options == "default" else f"_{options}"
            path = os.path.join(folder, f"sensitivity_{axis.replace(' + ', '+')}{suffix}.png")
            figure.savefig(path, dpi=100)
            plt.close(figure)
            written.append(path)
    return written
