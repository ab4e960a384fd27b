"""The statistics of a sweep's report (docs/SWEEPS.md): per scene, simulation set, option set and
formulation the mean, standard deviation and 95 % confidence interval over seeds; each
formulation against wc, paired by scene and seed, by the median difference (with its
distribution-free 95 % interval) and a Wilcoxon signed-rank test, Holm-corrected over the
comparisons made."""
import math

import numpy as np
from scipy import stats

# The metrics summarised and compared: (column, what it is).
METRICS = [
    ("camera_mean_rot_deg", "camera RPE rotation (deg)"),
    ("camera_mean_trans_m", "camera RPE translation (m)"),
    ("object_motion_mean_rot_deg", "object motion rotation (deg)"),
    ("object_motion_mean_trans_m", "object motion translation (m)"),
    ("object_pose_mean_rot_deg", "object pose rotation (deg)"),
    ("object_pose_mean_trans_m", "object pose translation (m)"),
    ("steps", "steps (linear solves)"),
    ("solve_time_s", "solve time (s)"),
]
# Summarised only (not tested against wc): the mean NEES per cell, when the option set asks for
# covariances (`covariance = "all"`) — its expected value is 6 (docs/COVARIANCE.md).
NEES = [
    ("camera_nees", "camera NEES"),
    ("object_motion_nees", "object motion NEES"),
    ("object_pose_nees", "object pose NEES"),
]
ALPHA = 0.05


def describe(values):
    """n, mean, sample standard deviation and the two-sided 95 % t interval of the mean (the
    interval and deviation are NaN for fewer than two values)."""
    x = np.asarray([v for v in values if v is not None], dtype=float)
    n = len(x)
    if n == 0:
        return {"n": 0, "mean": math.nan, "sd": math.nan, "ci_low": math.nan, "ci_high": math.nan}
    mean = float(np.mean(x))
    if n < 2:
        return {"n": 1, "mean": mean, "sd": math.nan, "ci_low": math.nan, "ci_high": math.nan}
    sd = float(np.std(x, ddof=1))
    half = float(stats.t.ppf(1 - ALPHA / 2, n - 1)) * sd / math.sqrt(n)
    return {"n": n, "mean": mean, "sd": sd, "ci_low": mean - half, "ci_high": mean + half}


def wilcoxon(differences):
    """Two-sided Wilcoxon signed-rank p-value of paired differences; 1.0 when every difference
    is zero (nothing to test: a formulation against itself) and NaN for no pairs."""
    d = np.asarray(differences, dtype=float)
    if len(d) == 0:
        return math.nan
    if not np.any(d != 0):
        return 1.0
    return float(stats.wilcoxon(d, zero_method="wilcox", alternative="two-sided").pvalue)


def holm(p_values):
    """Holm's step-down adjustment of p-values (NaN stays NaN), in the input's order."""
    indexed = [(p, i) for i, p in enumerate(p_values) if not math.isnan(p)]
    indexed.sort()
    adjusted = [math.nan] * len(p_values)
    running = 0.0
    m = len(indexed)
    for rank, (p, i) in enumerate(indexed):
        running = max(running, min(1.0, (m - rank) * p))
        adjusted[i] = running
    return adjusted


def simulation(row):
    """The row's simulation set ('default' for rows of a sweep without any)."""
    return row.get("simulate") or "default"


def setting_name(simulate, options):
    """How a report names a simulation set and option set ('default' parts left out)."""
    return " ".join(p for p in (simulate, options) if p != "default")


def median_interval(values):
    """The distribution-free 95 % interval of the median from order statistics (the binomial
    ranks that cover it with at least 95 %); NaN for fewer than 6 values, which cannot reach it."""
    x = np.sort(np.asarray(values, dtype=float))
    n = len(x)
    if n < 6:
        return math.nan, math.nan
    # The largest j with P(B ≤ j) ≤ α/2, B ~ Binomial(n, ½): the interval is the order statistics
    # of ranks j+1 and n−j (1-based), whose coverage is 1 − 2·P(B ≤ j) ≥ 95 %.
    low = int(stats.binom.ppf(ALPHA / 2, n, 0.5))
    if stats.binom.cdf(low, n, 0.5) > ALPHA / 2:
        low -= 1
    return float(x[low]), float(x[n - 1 - low])


def summarise(rows):
    """One dict per (scene, simulate, options, formulation, metric) over the seeds of finished
    cells."""
    groups = {}
    for row in rows:
        if row["status"] == "ok":
            key = (row["scene"], simulation(row), row["options"], row["formulation"])
            groups.setdefault(key, []).append(row)
    out = []
    for (scene, simulate, options, formulation), cells in sorted(groups.items()):
        for metric, _ in METRICS + NEES:
            values = [c.get(metric) for c in cells]
            if metric in dict(NEES) and all(v is None for v in values):
                continue
            out.append({"scene": scene, "simulate": simulate, "options": options,
                        "formulation": formulation, "metric": metric, **describe(values)})
    return out


def paired(rows, baseline="wc"):
    """Each formulation against `baseline` per simulation set, option set and metric, paired by
    scene and seed over every scene: median difference (formulation − baseline) and its 95 %
    interval, Wilcoxon p, Holm-adjusted p over all the comparisons returned, and whether that is
    below 0.05."""
    by_key = {}
    for row in rows:
        if row["status"] == "ok":
            setting = (simulation(row), row["options"])
            by_key[(setting, row["formulation"], row["scene"], row["seed"])] = row
    comparisons = []
    settings = sorted({k[0] for k in by_key})
    formulations = sorted({k[1] for k in by_key} - {baseline})
    for setting in settings:
        for formulation in formulations:
            for metric, _ in METRICS:
                differences = []
                for (s, f, scene, seed), row in by_key.items():
                    base = by_key.get((s, baseline, scene, seed))
                    if s != setting or f != formulation or base is None:
                        continue
                    if row[metric] is None or base[metric] is None:
                        continue
                    differences.append(row[metric] - base[metric])
                low, high = median_interval(differences)
                comparisons.append({
                    "simulate": setting[0], "options": setting[1], "formulation": formulation,
                    "baseline": baseline, "metric": metric, "pairs": len(differences),
                    "median_difference": float(np.median(differences)) if differences else math.nan,
                    "median_ci_low": low, "median_ci_high": high,
                    "p": wilcoxon(differences)})
    for comparison, adjusted in zip(comparisons, holm([c["p"] for c in comparisons])):
        comparison["p_holm"] = adjusted
        comparison["significant"] = bool(adjusted < ALPHA) if not math.isnan(adjusted) else False
    return comparisons
