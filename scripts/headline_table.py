#!/usr/bin/env python3
"""The headline table of README.md and BENCHMARKS.md, from the `ramap compare` reports that
scripts/benchmark.sh leaves (known intrinsics in build/bench, unknown in
build/bench-unknown-intrinsics): per data set and calibration, AUC@3 of COLMAP 3.8, COLMAP 4.1.1,
GLOMAP and ramap (averaging + BA, its default), ramap's wall time and its speed-up over COLMAP 3.8
and GLOMAP. The same reports make BENCHMARKS.md's full tables, so the two cannot disagree.

Usage: headline_table.py FILE [FILE ...]
  rewrites the table between <!-- headline-table:begin --> and <!-- headline-table:end --> in each
  FILE. RAMAP_BENCH_DIR / RAMAP_BENCH_UNKNOWN_DIR: the two benchmark folders; RAMAP_VERSION: the
  `ramap --version` of the binary that ran them (default: build/ramap's).
(standard library only)"""
import json
import os
import subprocess
import sys
import time

from benchmark_table import auc3, fmt, ratio, rewrite_between

BEGIN, END = "<!-- headline-table:begin -->", "<!-- headline-table:end -->"
PEERS = ["COLMAP", "COLMAP 4.1.1", "GLOMAP"]
RAMAP = "ramap+BA"


def reports(folder):
    """(data set name, report) of each data set under `folder` that has a compare report, the
    report's date (of its file) under "date"."""
    found = []
    if not os.path.isdir(folder):
        return found
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name, "compare", "report.json")
        if os.path.isfile(path):
            with open(path) as f:
                report = json.load(f)
            report["date"] = time.strftime("%Y-%m-%d", time.gmtime(os.path.getmtime(path)))
            found.append((name, report))
    return found


def auc3_cell(run):
    """The run's AUC@3, or why there is none: no such run, it failed, or it is the reference."""
    if run is None or not run["succeeded"]:
        return "failed" if run is not None else "-"
    return "(reference)" if not run.get("evaluation") else fmt(auc3(run), 1)


def rows(name, report, intrinsics):
    runs = {run["name"]: run for run in report["runs"]}
    ramap = runs.get(RAMAP)
    if ramap is None:
        return []
    cells = [name, str(report["num_images"]), intrinsics]
    cells += [auc3_cell(runs.get(peer)) for peer in PEERS] + [auc3_cell(ramap)]
    cells += [f"{ramap['seconds']:.1f}", ratio(ramap.get("speedup_over_colmap")),
              ratio(ramap.get("speedup_over_glomap"))]
    return ["| " + " | ".join(cells) + " |"]


def table(root):
    known = os.environ.get("RAMAP_BENCH_DIR", os.path.join(root, "build", "bench"))
    unknown = os.environ.get("RAMAP_BENCH_UNKNOWN_DIR",
                             os.path.join(root, "build", "bench-unknown-intrinsics"))
    lines = ["| data set | images | intrinsics | AUC@3: COLMAP 3.8 | COLMAP 4.1.1 | GLOMAP | ramap "
             "| ramap time (s) | ramap vs COLMAP 3.8 | ramap vs GLOMAP |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    by_name = {}
    dates = set()
    for label, folder in (("known", known), ("unknown", unknown)):
        for name, report in reports(folder):
            by_name.setdefault(name, []).extend(rows(name, report, label))
            dates.add(report["date"])
    for name in sorted(by_name, key=str.lower):
        lines += by_name[name]
    version = os.environ.get("RAMAP_VERSION")
    if not version:
        binary = os.path.join(root, "build", "ramap")
        version = subprocess.run([binary, "--version"], capture_output=True, text=True,
                                 check=False).stdout.strip() or "ramap (version unknown)"
    return "\n".join(lines) + (
        "\n\nAUC@3: relative-pose AUC at 3 degrees over all image pairs (%), against the data "
        "set's ground truth (sceaux_castle: against COLMAP 3.8's model). Times: each mapper as a "
        "whole process on the same COLMAP database, one run each; \"vs\" is how many times faster "
        f"ramap is. Made by {version} on {', '.join(sorted(dates))}, 2 cores, 24 GiB "
        "(`scripts/benchmark.sh`, then "
        "`scripts/headline_table.py`); every column of each run is in BENCHMARKS.md.\n")


def main(paths):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    text = table(root)
    print(text)
    for path in paths:
        rewrite_between(path, BEGIN, END, text)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
