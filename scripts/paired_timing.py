#!/usr/bin/env python3
"""Times two shell commands in paired, alternated runs (A B, B A, A B, ...) after one warm-up run
of each, so that a slow spell of the machine falls on both sides of a pair. Prints, for the wall
time of A, of B and the ratio A/B of each pair: "<what> wall <min> <median> <max>" (the rows
scripts/paired_ratio.awk reads).

Usage: paired_timing.py RUNS "A command" "B command"   (standard library only)"""
import statistics
import subprocess
import sys
import time


def wall_seconds(command):
    start = time.monotonic()
    finished = subprocess.run(command, shell=True, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True, check=False)
    seconds = time.monotonic() - start
    if finished.returncode != 0:
        sys.exit(f"paired_timing: exit {finished.returncode} from: {command}\n{finished.stderr}")
    return seconds


def row(what, values):
    return f"{what} wall {min(values):.4f} {statistics.median(values):.4f} {max(values):.4f}"


def main(runs, a, b):
    wall_seconds(a)
    wall_seconds(b)
    a_times, b_times = [], []
    for i in range(runs):
        if i % 2 == 0:
            a_times.append(wall_seconds(a))
            b_times.append(wall_seconds(b))
        else:
            b_times.append(wall_seconds(b))
            a_times.append(wall_seconds(a))
    print(row("A", a_times))
    print(row("B", b_times))
    print(row("A/B", [x / y for x, y in zip(a_times, b_times)]))


if __name__ == "__main__":
    if len(sys.argv) != 4 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit(__doc__)
    main(int(sys.argv[1]), sys.argv[2], sys.argv[3])
