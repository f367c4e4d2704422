#!/usr/bin/env bash
# How ramap's averaging holds up against aliased pairs (repeated facades matched to the wrong
# place): synthetic drives along KITTI 06's ground truth (1101 frames, as scripts/bench_scale.sh
# builds them: facades, 4-column keypoints, 0.7 px noise, 2% outlier matches, next 10 frames and
# revisits within 8 m), with a share of aliased pairs whose matches obey a relative rotation off by
# an angle in a range, then averaging alone (`ramap mapper --Mapper.refine 0
# --Mapper.subset_adjustment 0`) under four settings of the edge and row rejection:
#   paper     rotation pruning at the paper's fixed 45 deg alone (no direction check, no row
#             rejection)
#   fixed     fixed thresholds: rotation pruning at 45 deg, the cycle check of the pair
#             directions at 10 deg, and translation averaging's row rejection
#   default   ramap's defaults: rotation pruning and the cycle check at thresholds from the
#             residuals' median, and the row rejection
#   none      no rejection at all (no rotation pruning, no direction check, no row rejection)
# Prints one markdown row per drive: the ATE as a share of the path under each setting.
#
#   scripts/bench_robustness.sh                     none, then 3 10 20 % x angles 0-5 5-15 15-40
#   scripts/bench_robustness.sh 0.1:0:5 0.03:15:40  SHARE:MIN_DEG:MAX_DEG
#
# The aliased pairs are, by default, at most 30 frames apart and start from real observations, so
# their wrong matches join the tracks (RAMAP_ALIAS_ARGS replaces those synthesize options, e.g.
# "--Synthetic.aliased_max_frame_gap 0" for pairs anywhere). RAMAP_SEED (default 1) seeds the
# scenes, RAMAP_SEQUENCE:RAMAP_FRAMES the drive (default 06:1101). Scenes are cached under
# build/bench-robustness (RAMAP_ROBUST_DIR); RAMAP_DATA_DIR as elsewhere.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/datasets/kitti_drive.sh"
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
cache_dir=${RAMAP_ROBUST_DIR:-$root/build/bench-robustness}
ramap=${RAMAP_BINARY:-$root/build/ramap}
sequence=${RAMAP_SEQUENCE:-06}
frames=${RAMAP_FRAMES:-1101}
seed=${RAMAP_SEED:-1}
alias_args=${RAMAP_ALIAS_ARGS:---Synthetic.aliased_max_frame_gap 30 --Synthetic.aliased_matches_on_tracks 1 --Synthetic.num_aliased_pair_matches 300}
read -r -a alias_options <<<"$alias_args"
poses=$data_dir/gt_trajectories/kitti_odometry_poses/$sequence.txt
[[ -x $ramap ]] || { echo "bench_robustness: $ramap not built (run scripts/build.sh)" >&2; exit 1; }
[[ -f $poses ]] || { echo "bench_robustness: skipped, no KITTI trajectory $poses" >&2; exit 0; }
runs=("$@")
if ((${#runs[@]} == 0)); then
  runs=(0:0:5)  # no aliased pair: the angles do not matter
  for share in 0.03 0.10 0.20; do
    for range in 0:5 5:15 15:40; do runs+=("$share:$range"); done
  done
fi
declare -A settings=(
  [paper]="--RotationAveraging.pruning fixed --TranslationAveraging.direction_check off --TranslationAveraging.max_rejection_rounds 0"
  [fixed]="--RotationAveraging.pruning fixed --TranslationAveraging.direction_check fixed"
  [default]=""
  [none]="--RotationAveraging.max_pruning_rounds 0 --TranslationAveraging.direction_check off --TranslationAveraging.max_rejection_rounds 0"
)
order=(paper fixed default none)
mkdir -p "$cache_dir"

echo "| aliased pairs | angle off (deg) | paper | fixed | default | none |"
echo "| --- | --- | --- | --- | --- | --- |"
for run in "${runs[@]}"; do
  IFS=: read -r share min_deg max_deg <<<"$run"
  tag=$(echo "$alias_args" | md5sum | cut -c1-8)
  scene=$cache_dir/kitti${sequence}_${frames}_s${seed}_a${share}_${min_deg}-${max_deg}_$tag
  if [[ ! -f $scene/scene.done ]]; then
    rm -rf "$scene"
    synthesize_kitti_drive "$ramap" "$scene" "$poses" "$frames" $((20 * frames)) "$seed" 8 "$share" \
      --Synthetic.pixel_noise 0.7 --Synthetic.aliased_min_angle_deg "$min_deg" \
      --Synthetic.aliased_max_angle_deg "$max_deg" "${alias_options[@]}" > /dev/null
    touch "$scene/scene.done"
  fi
  row="| $(python3 -c "print(f'{100 * float(\"$share\"):g}%')") | $min_deg-$max_deg |"
  for name in "${order[@]}"; do
    read -r -a extra <<<"${settings[$name]}"
    out=$scene/sparse_$name
    rm -rf "$out" "$out.json"
    if "$ramap" mapper --database_path "$scene/database.db" --output_path "$out" \
        --Mapper.refine 0 --Mapper.subset_adjustment 0 --Mapper.num_threads 2 "${extra[@]}" > "$out.log" 2>&1 &&
       "$ramap" evaluate --model_path "$out/0" --ground_truth "$scene/ground_truth.txt" \
        --ground_truth_format tum --database_path "$scene/database.db" \
        --output_path "$out.json" > /dev/null 2>&1; then
      row+=" $(python3 -c "import json; e = json.load(open('$out.json')); print(f\"{100 * e['ate']['rmse_over_path_length']:.2f}% ({e['num_registered']})\")") |"
    else
      row+=" failed |"
    fi
  done
  echo "$row"
done
