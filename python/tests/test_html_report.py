"""The HTML reports (docs/GUIDE.md, "Reports") opened in a real browser: Debian's headless
Chromium loads each kind of page — compare's, one solve's, a sweep's — from file:// with every
host name unresolvable, and the page itself lists any script error, console error or blocked
request. Checks: no error, every plot drawn (the page's count against plotly's plot elements), a
screenshot that is not blank, a number of Table I equal to tables.csv's, and the size limits.
Needs DYNSLAM_CLI and PYTHONPATH as ctest sets them; scripts/test installs chromium."""
import csv
import io
import os
import re
import shutil
import subprocess
import sys

import pytest
from test_sweep import SIMULATION_SWEEP

CLI = os.environ.get("DYNSLAM_CLI")
CHROMIUM = shutil.which("chromium")
pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="no chromium (scripts/test installs it)")
MB = 1024 * 1024


def chromium(tmp_path, page, *args):
    """Runs headless Chromium on `page` with its own profile and no name resolution."""
    profile = tmp_path / f"profile-{len(list(tmp_path.iterdir()))}"
    command = [CHROMIUM, "--headless=new", "--no-sandbox", "--disable-gpu",
               f"--user-data-dir={profile}", "--host-resolver-rules=MAP * ~NOTFOUND",
               "--virtual-time-budget=30000", *args, f"file://{page}"]
    return subprocess.run(command, capture_output=True, timeout=240)


def rendered(tmp_path, page):
    """The page's DOM after its scripts ran."""
    result = chromium(tmp_path, page, "--dump-dom")
    assert result.returncode == 0, result.stderr.decode(errors="replace")[-2000:]
    return result.stdout.decode()


def check_page(tmp_path, page, min_plots):
    """No error on the page, every plot drawn, nothing fetched from elsewhere; the DOM."""
    with open(page, encoding="utf-8") as f:
        source = f.read()
    assert "Content-Security-Policy" in source
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=\"(https?:)?//", source)
    dom = rendered(tmp_path, page)
    errors = re.search(r'<div id="dynslam-errors">(.*?)</div>', dom, re.S)
    assert errors is not None and errors.group(1).strip() == "", errors and errors.group(1)
    plots = int(re.search(r'data-plots="(\d+)"', dom).group(1))
    drawn = int(re.search(r'data-drawn="(\d+)"', dom).group(1))
    assert plots >= min_plots and drawn == plots
    assert len(re.findall(r'class="[^"]*\bjs-plotly-plot\b', dom)) == plots
    assert dom.count('class="main-svg"') >= plots
    return dom


def check_screenshot(tmp_path, page):
    """A screenshot with content: many colours, not one blank or single-colour page."""
    from PIL import Image
    shot = tmp_path / f"shot-{os.path.basename(os.path.dirname(page))}.png"
    result = chromium(tmp_path, page, f"--screenshot={shot}", "--window-size=1280,1600")
    assert result.returncode == 0 and shot.is_file(), result.stderr.decode(errors="replace")[-2000:]
    image = Image.open(shot).convert("RGB")
    colours = image.getcolors(maxcolors=1 << 20)
    assert colours is not None and len(colours) > 200, "a blank screenshot"
    light = sum(n for n, rgb in colours if min(rgb) > 240)
    assert light < 0.97 * image.width * image.height, "an almost white screenshot"


def run(*args):
    result = subprocess.run([CLI, *args], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    return result


@pytest.fixture(scope="module")
def compare_dir(tmp_path_factory):
    """All five formulations on KITTI 0003, frames 0:60 (the size limit's case)."""
    work = tmp_path_factory.mktemp("compare")
    run("simulate", "--seq", "0003", "--frames", "0:60", "--seed", "1", "--out",
        str(work / "scene"))
    run("compare", str(work / "scene.g2o"), "--gt", str(work / "scene.gt.txt"), "--out",
        str(work / "cmp"), "--no-plots")
    return work / "cmp"


def test_compare_page_draws_everything_offline_and_shows_table_one(tmp_path, compare_dir):
    page = str(compare_dir / "report.html")
    assert os.path.getsize(page) <= 10 * MB
    dom = check_page(tmp_path, page, min_plots=6)
    with open(compare_dir / "tables.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    value = next(float(r["value"]) for r in rows if r["table"] == "I" and r["formulation"] == "oc_b"
                 and r["quantity"] == "camera_rot_deg")
    assert f"<td>oc_b</td><td>{value:.4f}</td>" in dom
    for formulation in ("wc", "oc_a", "oc_b", "oc_c", "hy"):  # a toggle per formulation
        assert f'value="g:{formulation}" checked' in dom
    check_screenshot(tmp_path, page)


def test_solve_page_with_covariances_draws_their_band(tmp_path, compare_dir):
    out = tmp_path / "solve"
    gt = str(compare_dir.parent / "scene.gt.txt")
    run("solve", str(compare_dir / "oc_b" / "graph.g2o"), "--gt", gt, "--out", str(out),
        "--covariance", "cameras", "--report")
    dom = check_page(tmp_path, str(out / "report.html"), min_plots=5)
    assert "3σ" in dom


def test_a_page_that_cannot_be_drawn_is_a_warning_not_a_failure(tmp_path, compare_dir):
    out = tmp_path / "solve"
    (tmp_path / "bad.gt.txt").write_text("CAMERA 0 not numbers\n")
    graph = str(compare_dir / "wc" / "graph.g2o")
    result = subprocess.run([CLI, "solve", graph, "--out", str(out), "--report",
                             "--max-iterations", "2"], capture_output=True, text=True)
    assert result.returncode == 0 and (out / "report.html").is_file(), result.stderr
    script = os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "html_report.py")
    result = subprocess.run(["/usr/bin/python3", script, str(out), "--gt",
                             str(tmp_path / "bad.gt.txt")], capture_output=True, text=True)
    assert result.returncode == 1
    assert result.stderr.startswith("warning: no report.html: ") and "bad.gt.txt:1:" in result.stderr
    assert "Traceback" not in result.stderr


SWEEP = SIMULATION_SWEEP + "[options.default]\n[options.paged]\nreport = true\n"


def test_sweep_page_links_each_cells_page(tmp_path):
    (tmp_path / "s.toml").write_text(SWEEP)
    out = tmp_path / "sweep"
    result = subprocess.run([sys.executable, "-m", "dynslam.sweep", str(tmp_path / "s.toml"),
                             "--out", str(out), "--workers", "2"], capture_output=True, text=True,
                            timeout=600)
    assert result.returncode == 0, result.stderr
    page = str(out / "report.html")
    dom = check_page(tmp_path, page, min_plots=8)  # a box plot per metric
    assert dom.count('href="cells/') == 72
    assert 'href="cells/synthetic_s1_pixel_2/oc_b_paged/report.html"' in dom
    assert 'href="cells/synthetic_s1/wc/summary.json"' in dom
    assert "Sensitivity to the simulator" in dom
    check_screenshot(tmp_path, page)
    check_page(tmp_path, str(out / "cells" / "synthetic_s2" / "wc_paged" / "report.html"),
               min_plots=5)
