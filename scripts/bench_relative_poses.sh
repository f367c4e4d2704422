#!/usr/bin/env bash
# The paper's relative-pose ablation on real data: grid / random / roi six-point selection and the
# RANSAC five-point baseline on every verified pair of each benchmark database, against ground
# truth (build/ramap_bench_relative_pose prints the table, one thread, time per pair).
#
#   scripts/bench_relative_poses.sh [NAME ...]     (databases from scripts/prepare_datasets.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}
source "$root/scripts/datasets/list.sh"
RAMAP_BENCH_DIR=$bench_dir bash "$root/scripts/prepare_datasets.sh" "$@" >&2
args=()
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name _ _ _ _ _ _ <<<"$entry"
  if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
  [[ -f $bench_dir/$name/database.done ]] || continue
  # shellcheck disable=SC1091
  source "$bench_dir/$name/dataset.env"
  [[ -n $ground_truth ]] || continue
  args+=("$name" "$bench_dir/$name/database.db" "$ground_truth" "$ground_truth_format")
done
((${#args[@]})) || { echo "bench_relative_poses: no prepared data set with ground truth" >&2; exit 1; }
"$root/build/ramap_bench_relative_pose" "${args[@]}"
