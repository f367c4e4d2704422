#!/usr/bin/env python3
"""What calling ramap from Python costs over the command line, on the prepared real databases.

For each database of build/KIND/NAME/database.db (scripts/prepare_datasets.sh makes them), the
two are run in turn, A B A B ..., as whole processes:
  A  python3 -c "import ramap; ramap.global_mapping(DB, '', OUT)"   (interpreter start and import
     included)
  B  ramap mapper --database_path DB --output_path OUT --log_level 0
with the same options (the defaults: averaging, then bundle adjustment, 2 threads). Each pair's
ratio A/B is one sample; the table gives the median wall times and the median ratio.

  scripts/bench_python_overhead.py [--runs N] [--kind bench|bench-unknown-intrinsics] [--names ...]
"""

import argparse
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
NAMES = ["fountain-P11", "Herz-Jesus-P8", "templeRing", "lund_door", "kitti07_first160",
         "sceaux_castle"]


def timed(command, env=None):
    start = time.monotonic()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=env)
    return time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="pairs per database (default 5)")
    parser.add_argument("--kind", default="bench", help="bench or bench-unknown-intrinsics")
    parser.add_argument("--names", nargs="*", default=NAMES, help="databases (default: all)")
    args = parser.parse_args()
    build = ROOT / "build"
    env = dict(os.environ, PYTHONPATH=str(build / "python"))
    print(f"{'database':18} {'CLI s':>8} {'Python s':>9} {'Python/CLI':>11}  (median of "
          f"{args.runs} alternated pairs, whole processes, {args.kind})")
    with tempfile.TemporaryDirectory() as work:
        for name in args.names:
            database = build / args.kind / name / "database.db"
            if not database.exists():
                print(f"{name:18} skipped: no {database}")
                continue
            out_python = pathlib.Path(work) / "python"
            out_cli = pathlib.Path(work) / "cli"
            python = ["/usr/bin/python3", "-c",
                      f"import ramap; ramap.global_mapping({str(database)!r}, '', "
                      f"{str(out_python)!r})"]
            cli = [str(build / "ramap"), "mapper", "--database_path", str(database),
                   "--output_path", str(out_cli), "--log_level", "0"]
            timed(python, env), timed(cli)  # warm-up: the files in the page cache
            python_times, cli_times, ratios = [], [], []
            for _ in range(args.runs):
                python_times.append(timed(python, env))
                cli_times.append(timed(cli))
                ratios.append(python_times[-1] / cli_times[-1])
            print(f"{name:18} {statistics.median(cli_times):8.2f} "
                  f"{statistics.median(python_times):9.2f} {statistics.median(ratios):11.3f}")
            shutil.rmtree(out_python, ignore_errors=True)
            shutil.rmtree(out_cli, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
