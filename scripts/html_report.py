#!/usr/bin/python3
"""The HTML report of a `dynslam compare` directory or of one `dynslam solve` directory:
DIR/report.html, self-contained (plotly.js embedded, no network). `dynslam compare` runs it after
its tables, `dynslam solve --report` after its outputs; a report that cannot be written is one
warning line (exit 1), never a failure of the solve.

    scripts/html_report.py cmp --labels wc oc_b --gt scene.gt.txt --title scene.g2o
    scripts/html_report.py solved --gt scene.gt.txt        # one solve: DIR itself
"""
import argparse
import importlib.util
import os
import sys

# The page is built by the Python package's _html module, loaded from the source tree by path
# (the package itself needs its compiled extension; this module does not).
HTML = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python", "dynslam",
                    "_html.py")


def load_html():
    spec = importlib.util.spec_from_file_location("dynslam_html", HTML)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dir", help="a compare's output directory, or a solve's")
    parser.add_argument("--labels", nargs="+",
                        help="the formulations' folders in DIR (none: DIR is one solve)")
    parser.add_argument("--gt", help="ground-truth file (SPEC §2)")
    parser.add_argument("--title", default="", help="the page's title")
    args = parser.parse_args()
    html = load_html()
    folders = [os.path.join(args.dir, label) for label in args.labels] if args.labels else [args.dir]
    labels = args.labels or [os.path.basename(os.path.normpath(args.dir))]
    tables = os.path.join(args.dir, "tables.md")
    out = os.path.join(args.dir, "report.html")
    try:
        tables_md = open(tables, encoding="utf-8").read() if os.path.isfile(tables) else None
        html.write(out, html.compare_page(folders, labels, args.gt, args.title, tables_md))
    except (html.ReportError, OSError) as error:
        sys.exit(f"warning: no report.html: {error}")
    print(f"[report] wrote {out}")


if __name__ == "__main__":
    main()
