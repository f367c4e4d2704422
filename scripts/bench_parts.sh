#!/usr/bin/env bash
# What each part of the mapper's back end buys: `ramap mapper` with its defaults (averaging, then
# bundle adjustment) on every prepared benchmark database, known intrinsics (build/bench) and
# unknown (build/bench-unknown-intrinsics), then the same with one part switched off (or, for BA
# rounds, one more), each evaluated against the data set's ground truth. Prints one markdown row
# per database: AUC@3 and wall time of the defaults, then of each variant.
#
#   scripts/bench_parts.sh [NAME ...]      (default: every prepared data set with a ground truth)
#
# Settings: RAMAP_BINARY (default build/ramap), RAMAP_DATA_DIR (default ../shared/data),
# KINDS ("bench bench-unknown-intrinsics" by default).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ramap=${RAMAP_BINARY:-$root/build/ramap}
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/datasets/list.sh"
variants=(
  "defaults|"
  "no final BA (the subset's only)|--Mapper.refine 0"
  "averaging alone|--Mapper.refine 0 --Mapper.subset_adjustment 0"
  "+1 BA round|--BundleAdjustment.num_rounds 2"
  "no filtering between BA's solves|--BundleAdjustment.max_reprojection_error_px 1e9"
  "points seen twice adjusted too|--BundleAdjustment.min_track_length 2"
  "loss scale 2 px (before)|--BundleAdjustment.loss_scale_px 2"
  "start bound 4 px (before)|--Triangulation.start_max_error_deg 0"
  "no wide start loss|--BundleAdjustment.wide_start_loss_factor 0"
  "no re-registration|--Reregistration.enable 0"
  "no test of given intrinsics (k1)|--BundleAdjustment.given_intrinsics_test 0"
  "no second averaging pass|--Mapper.max_focal_change_in_bundle_adjustment 0"
  "no calibration subset|--Mapper.calibration_num_points 0"
  "calibration pass on the full budgets|--Mapper.calibration_pass_num_tracks 0"
  "guessed principal point held|--BundleAdjustment.refine_guessed_principal_point 0"
)
header="| database |" separator="| --- |"
for variant in "${variants[@]}"; do
  header+=" ${variant%%|*}: AUC@3, s |"
  separator+=" --- |"
done
echo "$header"
echo "$separator"
for kind in ${KINDS:-bench bench-unknown-intrinsics}; do
  for entry in "${RAMAP_DATASETS[@]}"; do
    IFS='|' read -r name _ _ _ _ gt gt_format <<<"$entry"
    if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
    db=$root/build/$kind/$name/database.db
    [[ -f $db && -n $gt ]] || continue
    row="| ${kind#bench-}: $name |"
    [[ $kind == bench ]] && row="| known: $name |"
    for variant in "${variants[@]}"; do
      read -r -a options <<<"${variant#*|}"
      run=$work/run
      rm -rf "$run" "$run.json"
      start=$(date +%s.%N)
      if ! "$ramap" mapper --database_path "$db" --output_path "$run" --log_level 0 \
        "${options[@]}" > "$work/log" 2>&1; then
        row+=" failed |"
        continue
      fi
      end=$(date +%s.%N)
      "$ramap" evaluate --model_path "$run/0" --ground_truth "$data_dir/$gt" \
        --ground_truth_format "$gt_format" --database_path "$db" --output_path "$run.json" \
        > /dev/null
      auc=$(python3 -c 'import json, sys
print("%.1f" % (100 * json.load(open(sys.argv[1]))["relative"]["auc_by_threshold_deg"]["3"]))' \
        "$run.json")
      row+=" $auc, $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') |"
    done
    echo "$row"
  done
done
