#!/usr/bin/env python3
"""Markdown tables of one scripts/benchmark.sh run: accuracy and wall time of `colmap mapper`,
`ramap mapper` and `ramap mapper --Mapper.refine 1` on the same database, side by side, with the
speed ratios. Arguments: the data sets' benchmark folders. Standard library only."""
import json
import os
import sys

VARIANTS = [("colmap", "COLMAP"), ("ramap", "ramap"), ("ramap_ba", "ramap+BA")]


def read_env(path):
    env = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            env[key] = value
    return env


def read_seconds(path):
    try:
        with open(path) as f:
            return float(f.read().strip())
    except (OSError, ValueError):
        return None


def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def fmt(value, digits=2, suffix=""):
    return "-" if value is None else f"{value:.{digits}f}{suffix}"


def main(folders):
    accuracy = [
        "| data set | images | variant | registered | AUC@1 | AUC@3 | AUC@5 | rot. err. median (deg) "
        "| rel. rot. err. median (deg) | ATE RMSE | ATE / path | ATE / extent |",
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    timing = [
        "| data set | features + matching (s, COLMAP) | COLMAP mapper (s) | ramap (s) | ramap+BA (s) "
        "| speed-up ramap | speed-up ramap+BA |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for folder in folders:
        env = read_env(os.path.join(folder, "dataset.env"))
        name = env.get("name", os.path.basename(folder))
        seconds = {v: read_seconds(os.path.join(folder, v + ".seconds")) for v, _ in VARIANTS}
        origin = ""
        try:
            with open(os.path.join(folder, "colmap.origin")) as f:
                if f.read().strip() == "reused":
                    origin = " (reused)"
        except OSError:
            pass
        for variant, label in VARIANTS:
            report = read_json(os.path.join(folder, variant + ".eval.json"))
            if report is None:
                state = "failed" if seconds[variant] is None else "no ground truth"
                accuracy.append(f"| {name} | - | {label} | {state} | | | | | | | | |")
                continue
            auc = report["relative"]["auc_by_threshold_deg"]
            ate = report["ate"]
            accuracy.append(
                f"| {name} | {report['num_images']} | {label} | {report['num_registered']} "
                f"| {fmt(100 * auc['1'], 1)} | {fmt(100 * auc['3'], 1)} | {fmt(100 * auc['5'], 1)} "
                f"| {fmt(report['rotation_error_deg']['median'], 3)} "
                f"| {fmt(report['relative']['rotation_error_median_deg'], 3)} | {fmt(ate['rmse'], 4)} "
                f"| {fmt(100 * ate['rmse_over_path_length'], 2, '%')} "
                f"| {fmt(100 * ate['rmse_over_extent'], 2, '%')} |")
        colmap_s = seconds["colmap"]

        def ratio(v):
            if colmap_s is None or seconds[v] is None or seconds[v] <= 0:
                return "-"
            return f"{colmap_s / seconds[v]:.1f}x"

        timing.append(
            f"| {name} | {env.get('features_and_matching_seconds', '-')} | {fmt(colmap_s)}{origin} "
            f"| {fmt(seconds['ramap'])} | {fmt(seconds['ramap_ba'])} | {ratio('ramap')} "
            f"| {ratio('ramap_ba')} |")
    print("Accuracy (AUC in %; rotation error after Sim(3) alignment of the camera centres; "
          "relative rotation error over all image pairs, free of any alignment; ATE in "
          "ground-truth units):\n")
    print("\n".join(accuracy))
    print("\nWall time of each mapper as a whole process, and COLMAP's time over ramap's:\n")
    print("\n".join(timing))


if __name__ == "__main__":
    main(sys.argv[1:])
