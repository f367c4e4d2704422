#!/usr/bin/env bash
# From images to a model, timed end to end on the same images with the same known intrinsics:
# COLMAP (feature_extractor + matcher + mapper, CPU) vs `ramap reconstruct` with ORB and with SIFT.
# Each result is evaluated against the ground truth with `ramap evaluate`; the table is printed.
#
#   scripts/bench_image_input.sh [NAME ...]     (default: templeRing kitti07_first160)
#
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench),
# RAMAP_MAX_IMAGE_SIZE (default 1600), RAMAP_MAX_NUM_FEATURES (ramap, default 4000).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/image_input
ramap=$root/build/ramap
max_image_size=${RAMAP_MAX_IMAGE_SIZE:-1600}
max_num_features=${RAMAP_MAX_NUM_FEATURES:-4000}
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(templeRing kitti07_first160)

seconds_of() {  # runs "$@" quietly, prints its wall time in seconds (or "failed")
  local start end
  start=$(date +%s%N)
  if ! "$@" >/dev/null 2>&1; then echo failed; return 0; fi
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'
}

row() {  # name variant seconds model
  local model=$4 report=$bench_dir/$1/$2.eval.json
  if [[ ! -f $model/images.bin ]]; then
    echo "| $1 | $2 | failed | | | | | $3 |"
    return
  fi
  "$ramap" evaluate --model_path "$model" --ground_truth "$data_dir/$gt" \
    --ground_truth_format "$gt_format" --database_path "$5" --output_path "$report" >/dev/null
  python3 - "$report" "$1" "$2" "$3" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
auc = r["relative"]["auc_by_threshold_deg"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {r['num_registered']} / {r['num_images']} "
      f"| {100 * auc['1']:.1f} | {100 * auc['5']:.1f} | {r['rotation_error_deg']['median']:.3f} "
      f"| {100 * r['ate']['rmse_over_path_length']:.2f}% | {sys.argv[4]} |")
PY
}

echo "| data set | pipeline | registered | AUC@1 | AUC@5 | rot. err. median (deg) | ATE / path | images to model (s) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images model params matcher gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  [[ -d $data_dir/$images ]] || { echo "bench_image_input: $name: no images, skipped" >&2; continue; }
  out=$bench_dir/$name
  rm -rf "$out" && mkdir -p "$out/images" "$out/colmap_sparse"
  find "$data_dir/$images" -maxdepth 1 -type f \( -iname '*.png' -o -iname '*.jpg' \) \
    -exec ln -s {} "$out/images/" \;
  mode=exhaustive
  [[ $matcher == sequential ]] && mode=sequential
  colmap_pipeline() {
    colmap feature_extractor --database_path "$out/colmap.db" --image_path "$out/images" \
      --ImageReader.single_camera 1 --ImageReader.camera_model "$model" \
      --ImageReader.camera_params "$params" --SiftExtraction.use_gpu 0 \
      --SiftExtraction.max_image_size "$max_image_size" &&
      colmap "${matcher}_matcher" --database_path "$out/colmap.db" --SiftMatching.use_gpu 0 &&
      colmap mapper --database_path "$out/colmap.db" --image_path "$out/images" \
        --output_path "$out/colmap_sparse" --Mapper.num_threads 2 \
        --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0 \
        --Mapper.ba_refine_extra_params 0
  }
  seconds=$(seconds_of colmap_pipeline)
  row "$name" "COLMAP (SIFT, $matcher)" "$seconds" "$out/colmap_sparse/0" "$out/colmap.db"
  for type in orb sift; do
    for refine in 0 1; do
      variant="ramap reconstruct ($type, $mode)"
      if [[ $refine == 1 ]]; then variant="ramap reconstruct ($type, $mode, +BA)"; fi
      dir=$out/ramap_${type}_$refine
      seconds=$(seconds_of "$ramap" reconstruct --image_path "$out/images" --output_path "$dir" \
        --ImageReader.single_camera 1 --ImageReader.camera_model "$model" \
        --ImageReader.camera_params "$params" --FeatureExtraction.type "$type" \
        --FeatureExtraction.max_image_size "$max_image_size" \
        --FeatureExtraction.max_num_features "$max_num_features" --Matching.mode "$mode" \
        --Mapper.refine "$refine")
      row "$name" "$variant" "$seconds" "$dir/sparse/0" "$dir/database.db"
    done
  done
done
