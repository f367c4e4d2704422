#!/usr/bin/env bash
# Matching plans side by side on the same features: exhaustive, sequential and retrieval, each
# with the pairs it matched and verified, the share of the covisible pairs it verified, its time,
# and the mapper's accuracy on what it matched.
#
#   scripts/bench_matching_plans.sh [NAME ...]     (default: kitti07_first160 templeRing)
#
# Covisible pairs: those that full matching of every pair (no preemptive screening) verifies with
# at least 15 inliers ("strong": 100). Features: `ramap feature_extractor` with its defaults and
# the data set's calibration (one camera). Each plan: `ramap matcher --Matching.mode M`, timed,
# then `ramap mapper` with its defaults and `ramap evaluate` against the ground truth.
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/matching_plans
ramap=$root/build/ramap
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(kitti07_first160 templeRing)

seconds_of() {  # runs "$@" with its output in $log, prints its wall time in seconds
  local start end
  start=$(date +%s%N)
  "$@" >"$log" 2>&1 || { echo failed; return 0; }
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'
}

verified_pairs() {  # database -> "image_id1 image_id2 inliers" per verified pair
  python3 - "$1" <<'PY'
import sqlite3, sys
db = sqlite3.connect(sys.argv[1])
for pair_id, rows in db.execute("SELECT pair_id, rows FROM two_view_geometries WHERE rows > 0"):
    print(pair_id // 2147483647, pair_id % 2147483647, rows)
PY
}

echo "| data set | plan | pairs matched in full | pairs verified | recall of covisible pairs | recall of strong pairs | matching (s) | AUC@3 after the mapper |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images camera_model params matcher gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  [[ -d $data_dir/$images ]] || { echo "bench_matching_plans: $name: no images, skipped" >&2; continue; }
  out=$bench_dir/$name
  rm -rf "$out" && mkdir -p "$out"
  log=$out/features.log
  "$ramap" feature_extractor --image_path "$data_dir/$images" --database_path "$out/features.db" \
    --ImageReader.camera_model "$camera_model" --ImageReader.camera_params "$params" \
    --ImageReader.single_camera 1 >"$log" 2>&1
  cp "$out/features.db" "$out/all_pairs.db"
  log=$out/all_pairs.log
  all_seconds=$(seconds_of "$ramap" matcher --database_path "$out/all_pairs.db" \
    --Matching.mode exhaustive --Matching.preemptive_num_features 0)
  verified_pairs "$out/all_pairs.db" >"$out/covisible.txt"
  plans=("exhaustive|--Matching.mode exhaustive" "sequential|--Matching.mode sequential"
    "retrieval (30 neighbours)|--Matching.mode retrieval"
    "retrieval (10 neighbours)|--Matching.mode retrieval --Matching.retrieval_num_neighbors 10"
    "auto (the default)|")
  for plan in "every pair, unscreened|" "${plans[@]}"; do
    IFS='|' read -r label options <<<"$plan"
    dir=$out/$(echo "$label" | tr -c 'a-zA-Z0-9' _)
    mkdir -p "$dir"
    if [[ $label == every* ]]; then
      cp "$out/all_pairs.db" "$dir/database.db"
      seconds=$all_seconds
      cp "$out/all_pairs.log" "$dir/matcher.log"
    else
      cp "$out/features.db" "$dir/database.db"
      log=$dir/matcher.log
      # shellcheck disable=SC2086
      seconds=$(seconds_of "$ramap" matcher --database_path "$dir/database.db" $options)
    fi
    verified_pairs "$dir/database.db" >"$dir/verified.txt"
    matched=$(grep -o 'of [0-9]* pairs verified' "$dir/matcher.log" | awk '{print $2}')
    auc=""
    if "$ramap" mapper --database_path "$dir/database.db" --output_path "$dir/sparse" \
      >"$dir/mapper.log" 2>&1 && [[ -n $gt ]]; then
      "$ramap" evaluate --model_path "$dir/sparse/0" --ground_truth "$data_dir/$gt" \
        --ground_truth_format "$gt_format" --database_path "$dir/database.db" \
        --output_path "$dir/eval.json" >/dev/null
      auc=$(python3 -c "import json,sys; print('%.1f' % (100 * json.load(open(sys.argv[1]))['relative']['auc_by_threshold_deg']['3']))" "$dir/eval.json")
    fi
    python3 - "$out/covisible.txt" "$dir/verified.txt" "$name" "$label" "$matched" "$seconds" "$auc" <<'PY'
import sys
covisible_file, verified_file, name, label, matched, seconds, auc = sys.argv[1:8]
def load(path):
    pairs = {}
    for line in open(path):
        a, b, n = map(int, line.split())
        pairs[(a, b)] = n
    return pairs
covisible, verified = load(covisible_file), load(verified_file)
strong = {p for p, n in covisible.items() if n >= 100}
recall = sum(p in verified for p in covisible) / max(1, len(covisible))
strong_recall = sum(p in verified for p in strong) / max(1, len(strong))
print(f"| {name} | {label} | {matched} | {len(verified)} | {100 * recall:.1f}% of {len(covisible)} | "
      f"{100 * strong_recall:.1f}% of {len(strong)} | {seconds} | {auc} |")
PY
  done
done
