#!/usr/bin/env bash
# COLMAP's BA mapper vs ramap's averaging mapper (with and without --Mapper.refine 1) on the SAME
# COLMAP database of each benchmark data set, in one run: each mapper is timed as a whole process,
# each model evaluated against the data set's ground truth with `ramap evaluate`, and the table
# (with speed ratios) printed and written to build/bench/results.md.
#
#   scripts/benchmark.sh [NAME ...]            (default: every prepared data set)
#
# Databases come from scripts/prepare_datasets.sh (run first; cached). Intrinsics stay fixed in both
# mappers, as ../shared/data/README.md asks. Settings: RAMAP_BENCH_DIR (default build/bench),
# RAMAP_BENCH_SKIP_COLMAP=1 reuses the COLMAP models of an earlier run (the table says so).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}
ramap=${RAMAP_BINARY:-$root/build/ramap}
source "$root/scripts/datasets/list.sh"
[[ -x $ramap ]] || { echo "benchmark: $ramap not built (run scripts/build.sh)" >&2; exit 1; }

# Runs a command, writing its output to a log and its wall time (seconds) to a file.
timed() {
  local seconds_file=$1 log=$2
  shift 2
  local start end
  start=$(date +%s%N)
  if ! "$@" >"$log" 2>&1; then
    echo "failed" >"$seconds_file"
    echo "benchmark: failed: $* (log: $log)" >&2
    return 0
  fi
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f\n", (b - a) / 1e9 }' >"$seconds_file"
}

# Evaluates the largest model under a mapper's output folder (COLMAP numbers models by creation,
# not size) against the ground truth.
evaluate() {
  local sparse=$1 out_json=$2
  rm -f "$out_json"
  [[ -n $ground_truth ]] || return 0
  local best="" best_count=-1 model count
  for model in "$sparse"/*/; do
    [[ -f $model/images.bin ]] || continue
    count=$(od -An -t u8 -N 8 "$model/images.bin" | tr -d ' ')  # images.bin starts with the count
    if ((count > best_count)); then best=$model best_count=$count; fi
  done
  [[ -n $best ]] || return 0
  "$ramap" evaluate --model_path "$best" --ground_truth "$ground_truth" \
    --ground_truth_format "$ground_truth_format" --database_path "$db" \
    --output_path "$out_json" >"${out_json%.json}.log" 2>&1 || true
}

ran=()
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name _ _ _ _ _ _ <<<"$entry"
  if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
  dir=$bench_dir/$name
  if [[ ! -f $dir/database.done ]]; then
    echo "benchmark: $name: no database (run scripts/prepare_datasets.sh $name), skipped" >&2
    continue
  fi
  # shellcheck disable=SC1091
  source "$dir/dataset.env"
  db=$dir/database.db
  echo "benchmark: $name"

  if [[ ${RAMAP_BENCH_SKIP_COLMAP:-0} != 1 || ! -f $dir/colmap.seconds ]]; then
    rm -rf "$dir/colmap" && mkdir -p "$dir/colmap"
    timed "$dir/colmap.seconds" "$dir/colmap.log" colmap mapper --database_path "$db" \
      --image_path "$images" --output_path "$dir/colmap" --Mapper.num_threads 2 \
      --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0 \
      --Mapper.ba_refine_extra_params 0
    echo fresh >"$dir/colmap.origin"
  else
    echo reused >"$dir/colmap.origin"
  fi
  timed "$dir/ramap.seconds" "$dir/ramap.log" "$ramap" mapper --database_path "$db" \
    --output_path "$dir/ramap"
  timed "$dir/ramap_ba.seconds" "$dir/ramap_ba.log" "$ramap" mapper --database_path "$db" \
    --output_path "$dir/ramap_ba" --Mapper.refine 1

  for variant in colmap ramap ramap_ba; do
    evaluate "$dir/$variant" "$dir/$variant.eval.json"
  done
  ran+=("$dir")
done

((${#ran[@]})) || { echo "benchmark: nothing ran" >&2; exit 1; }
python3 "$root/scripts/benchmark_table.py" "${ran[@]}" | tee "$bench_dir/results.md"
