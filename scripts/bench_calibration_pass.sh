#!/usr/bin/env bash
# Whether a calibration pass's smaller budgets (--Mapper.calibration_pass_num_tracks) cost the
# second pass accuracy: synthetic scenes whose views fixate one point from one distance (where the
# view graph cannot estimate the focal length, as on a turntable; scripts/fixating_scene.py), each
# from half and from 1.6 times its focal length, with the true principal point 10 px and 6 px from
# the image's centre where the database guesses it. `ramap mapper` with its defaults against
# `--Mapper.calibration_pass_num_tracks 0` (the calibration pass on the second pass's budgets),
# one thread each, scored against the scene's truth. Prints one markdown row per scene and the
# means.
#
#   scripts/bench_calibration_pass.sh [SEED ...]      (default: seeds 1 to 6)
#
# Settings: RAMAP_BINARY (default build/ramap); RAMAP_MAPPER_ARGS: options added to the first
# column's run; RAMAP_BASELINE_ARGS: the second column's options instead of
# `--Mapper.calibration_pass_num_tracks 0`.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ramap=${RAMAP_BINARY:-$root/build/ramap}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
read -r -a mapper_args <<< "${RAMAP_MAPPER_ARGS:-}"
read -r -a baseline_args <<< "${RAMAP_BASELINE_ARGS:---Mapper.calibration_pass_num_tracks 0}"
seeds=("$@")
((${#seeds[@]})) || seeds=(1 2 3 4 5 6)
# name|views|arc (deg)|distance|elevation swing (deg)
layouts=("ring36|36|360|10|20" "flat ring47|47|360|9.5|4" "arc24|24|180|10|12")

# AUC@3 (%) and the mapper's wall seconds of one run, or "failed".
run() {
  local db=$1 truth=$2 out=$3
  shift 3
  local start end
  start=$(date +%s.%N)
  if ! "$ramap" mapper --database_path "$db" --output_path "$out" --Mapper.num_threads 1 \
    --log_level 0 "$@" > "$out.log" 2>&1; then
    echo "failed"
    return
  fi
  end=$(date +%s.%N)
  "$ramap" evaluate --model_path "$out/0" --ground_truth "$truth" --ground_truth_format colmap \
    --output_path "$out.json" > /dev/null
  python3 - "$out.json" "$out/summary.json" "$start" "$end" << 'PY'
import json, sys
auc = json.load(open(sys.argv[1]))["relative"]["auc_by_threshold_deg"]["3"]
summary = json.load(open(sys.argv[2]))
passes = summary.get("first_pass_only_calibrated", False)
print("%.2f, %.2f s%s" % (100 * auc, float(sys.argv[4]) - float(sys.argv[3]),
                          "" if passes else " (no calibration pass)"))
PY
}

echo "| scene | seed | guess | defaults ${mapper_args[*]}: AUC@3, s | ${baseline_args[*]}: AUC@3, s |"
echo "| --- | --- | --- | --- | --- |"
declare -a default_aucs=() baseline_aucs=()
for layout in "${layouts[@]}"; do
  IFS='|' read -r name views arc distance elevation <<< "$layout"
  trajectory=$work/${name// /_}.txt
  python3 "$root/scripts/fixating_scene.py" trajectory "$trajectory" --num_views "$views" \
    --arc_deg "$arc" --distance "$distance" --elevation_deg "$elevation"
  for seed in "${seeds[@]}"; do
    scene=$work/${name// /_}_$seed
    "$ramap" synthesize --output_path "$scene" --Synthetic.trajectory_path "$trajectory" \
      --Synthetic.num_images 0 --Synthetic.num_points 3000 --Synthetic.seed "$seed" \
      --Synthetic.camera_params 1500,1500,330,234 --Synthetic.min_depth 7 \
      --Synthetic.max_depth 13 --Synthetic.overlap 6 > /dev/null
    for guess in 0.5 1.6; do
      db=$scene/guess_$guess.db
      cp "$scene/database.db" "$db"
      python3 "$root/scripts/fixating_scene.py" unknown "$db" --guess_factor "$guess"
      defaults=$(run "$db" "$scene/ground_truth" "$scene/defaults_$guess" "${mapper_args[@]}")
      baseline=$(run "$db" "$scene/ground_truth" "$scene/baseline_$guess" "${baseline_args[@]}")
      echo "| $name | $seed | $guess | $defaults | $baseline |"
      default_aucs+=("${defaults%%,*}")
      baseline_aucs+=("${baseline%%,*}")
    done
  done
done
python3 - "${default_aucs[*]}" "${baseline_aucs[*]}" << 'PY'
import sys
def mean(values):
    numbers = [float(v) for v in values.split() if v != "failed"]
    return sum(numbers) / len(numbers), len(numbers)
for label, values in (("first column", sys.argv[1]), ("second column", sys.argv[2])):
    m, n = mean(values)
    print("\nmean AUC@3, %s: %.2f over %d scenes" % (label, m, n), end="")
print()
PY
