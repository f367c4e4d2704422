#!/usr/bin/env python3
"""The mapper table of one scripts/benchmark.sh run, from each data set's `ramap compare`
report.json: accuracy and wall time of `colmap mapper`, the peers when they ran (COLMAP 4.1.1's
`mapper` and `global_mapper` = GLOMAP), `ramap mapper --Mapper.refine 0` and `ramap mapper` on
the same database, side by side, with the speed ratios (and, with GLOMAP, a line of the ratios
against it at each one's AUC@3). Prints it and
rewrites it in BENCHMARKS.md between the mapper-table markers (with --intrinsics unknown: the
unknown-intrinsics table, with each mapper's focal length error against the known calibration).

Usage: benchmark_table.py [--intrinsics known|unknown] BENCHMARKS.md FOLDER [FOLDER ...]
(standard library only)"""
import json
import os
import platform
import sys
import time

MARKERS = {
    "known": ("<!-- mapper-table:begin -->", "<!-- mapper-table:end -->"),
    "unknown": ("<!-- unknown-intrinsics-table:begin -->", "<!-- unknown-intrinsics-table:end -->"),
}


def read_env(path):
    env = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            env[key] = value
    return env


def fmt(value, digits=2, suffix=""):
    return "-" if value is None else f"{value:.{digits}f}{suffix}"


def percent(value):
    """A fraction as a percentage; None (e.g. the ATE of two registered images) stays None."""
    return None if value is None else 100 * value


def focal_error(env, run):
    """Error (%) of the run's focal length against the data set's known one (its first
    parameter: f or fx), for the single camera these databases have."""
    focal = run.get("focal_lengths_px", {})
    if not focal or not env.get("camera_params"):
        return "-"
    truth = float(env["camera_params"].split(",")[0])
    estimate = next(iter(focal.values()))
    return f"{100 * (estimate / truth - 1):+.2f}%"


def auc3(run):
    e = run.get("evaluation")
    return None if not e else 100 * e["relative"]["auc_by_threshold_deg"]["3"]


def ratio(value):
    return "-" if value is None else f"{value:.1f}x"


def glomap_line(name, report):
    """'name: GLOMAP AUC@3 a in s s; ramap+BA 12.0x as fast at AUC@3 b; ...', or None."""
    runs = report["runs"]
    names = [run["name"] for run in runs]
    if "GLOMAP" not in names:
        return None
    glomap = runs[names.index("GLOMAP")]
    if not glomap["succeeded"]:
        return f"- {name}: GLOMAP failed."
    parts = [f"{run['name']} {ratio(run.get('speedup_over_glomap'))} as fast at AUC@3 "
             f"{fmt(auc3(run), 1)}" for run in runs[names.index("GLOMAP") + 1:]]
    return (f"- {name}: GLOMAP AUC@3 {fmt(auc3(glomap), 1)} in {fmt(glomap['seconds'])} s; "
            + "; ".join(parts) + ".")


def table(folders, unknown):
    reports = []
    for folder in folders:
        env = read_env(os.path.join(folder, "dataset.env"))
        with open(os.path.join(folder, "compare", "report.json")) as f:
            reports.append((env.get("name", os.path.basename(folder)), env, json.load(f)))
    with_glomap = any(run["name"] == "GLOMAP" for _, _, report in reports for run in report["runs"])
    focal_header = " focal error |" if unknown else ""
    rows = [
        "| data set | images | mapper |" + focal_header + " registered | AUC@1 | AUC@3 | AUC@5 "
        "| rot. err. median (deg) | rel. rot. err. median (deg) | ATE RMSE | ATE / path "
        "| ATE / extent | wall time (s) | speed-up over COLMAP |"
        + (" speed-up over GLOMAP |" if with_glomap else ""),
        "|" + " --- |" * (14 + unknown + with_glomap),
    ]
    glomap_lines = []
    for name, env, report in reports:
        line = glomap_line(name, report)
        if line:
            glomap_lines.append(line)
        for run in report["runs"]:
            registered = f"{run['num_registered']}" if run["succeeded"] else "failed"
            speedup = run.get("speedup_over_colmap")
            cells = [name, str(report["num_images"]), run["name"]]
            if unknown:
                cells.append(focal_error(env, run))
            cells.append(registered)
            e = run.get("evaluation")
            if e:
                auc = e["relative"]["auc_by_threshold_deg"]
                ate = e["ate"]
                cells += [fmt(100 * auc["1"], 1), fmt(100 * auc["3"], 1), fmt(100 * auc["5"], 1),
                          fmt(e["rotation_error_deg"]["median"], 3),
                          fmt(e["relative"]["rotation_error_median_deg"], 3), fmt(ate["rmse"], 4),
                          fmt(percent(ate["rmse_over_path_length"]), 2, "%"),
                          fmt(percent(ate["rmse_over_extent"]), 2, "%")]
            else:
                cells += ["", "", "", "(reference)", "", "", "", ""]
            cells += [fmt(run["seconds"]), ratio(speedup)]
            if with_glomap:
                cells.append(ratio(run.get("speedup_over_glomap")))
            rows.append("| " + " | ".join(cells) + " |")
    reference = ("Reference: the data set's ground truth; sceaux_castle has none, so its ramap "
                 "models are scored against COLMAP's (`ramap compare` without --ground_truth).")
    stamp = time.strftime("%Y-%m-%d", time.gmtime())
    version = os.environ.get("RAMAP_VERSION", "ramap (version unknown)")
    text = "\n".join(rows) + f"\n\n{reference} Run on {stamp} with {version}, " \
        f"{os.cpu_count()} cores, {platform.machine()}.\n"
    if glomap_lines:
        text += "\nAgainst GLOMAP, at each one's AUC@3:\n\n" + "\n".join(glomap_lines) + "\n"
    return text


def rewrite_between(path, begin, end, text):
    """Replaces what stands between the markers `begin` and `end` in the file `path` by `text`
    (written whole, then renamed into place); exits naming the file when a marker is missing."""
    with open(path) as f:
        content = f.read()
    if begin not in content or end not in content:
        sys.exit(f"{path}: no {begin} ... {end} markers; table printed only")
    head, rest = content.split(begin, 1)
    _, tail = rest.split(end, 1)
    with open(path + ".tmp", "w") as f:
        f.write(head + begin + "\n" + text + end + tail)
    os.replace(path + ".tmp", path)


def main(benchmarks, folders, intrinsics):
    text = table(folders, intrinsics == "unknown")
    print(text)
    rewrite_between(benchmarks, *MARKERS[intrinsics], text)


if __name__ == "__main__":
    args = sys.argv[1:]
    intrinsics = "known"
    if args[:1] == ["--intrinsics"] and len(args) > 1:
        intrinsics, args = args[1], args[2:]
    if len(args) < 2 or intrinsics not in MARKERS:
        sys.exit(__doc__)
    main(args[0], args[1:], intrinsics)
