#!/usr/bin/env bash
# From images to model, timed the way speed ratios are quoted: `ramap reconstruct` against COLMAP
# 3.8's pipeline (feature_extractor + the data set's matcher + mapper, CPU), both as
# scripts/bench_image_input.sh runs them, in paired, alternated runs (A B A B ...);
# the median of the pairs' ratios is printed per data set. Each run starts from an empty folder.
#
#   scripts/bench_from_images_paired.sh [NAME ...]   (default: templeRing lund_door)
#
# Settings: RAMAP_INTRINSICS=known (default) or unknown, as bench_image_input.sh (whose image
# folders under build/bench it reuses: run it first); RAMAP_RUNS (default 3).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
intrinsics=${RAMAP_INTRINSICS:-known}
runs=${RAMAP_RUNS:-3}
suffix=""
[[ $intrinsics == known ]] || suffix="-$intrinsics-intrinsics"
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/image_input$suffix
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(templeRing lund_door)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| data set | intrinsics | ramap wall (s) | COLMAP wall (s) | COLMAP / ramap (median of pairs) | min-max |"
echo "| --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images camera_model params matcher gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  images=$bench_dir/$name/images
  [[ -d $images ]] || { echo "bench_from_images_paired: $name: no $images, skipped" >&2; continue; }
  colmap_camera="--ImageReader.single_camera 1"
  colmap_fixed="" ramap_camera="--ImageReader.single_camera 1"
  if [[ $intrinsics == known ]]; then
    colmap_camera+=" --ImageReader.camera_model $camera_model --ImageReader.camera_params $params"
    colmap_fixed="--Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0"
    ramap_camera+=" --ImageReader.camera_model $camera_model --ImageReader.camera_params $params --FeatureExtraction.max_num_features ${RAMAP_MAX_NUM_FEATURES:-4000}"
  fi
  out=$work/$name
  ramap_cmd="rm -rf $out/ramap && exec $root/build/ramap reconstruct --image_path $images --output_path $out/ramap $ramap_camera"
  colmap_cmd="rm -rf $out/colmap && mkdir -p $out/colmap/sparse && colmap feature_extractor --database_path $out/colmap/db --image_path $images $colmap_camera --SiftExtraction.use_gpu 0 --SiftExtraction.max_image_size 1600 && colmap ${matcher}_matcher --database_path $out/colmap/db --SiftMatching.use_gpu 0 && colmap mapper --database_path $out/colmap/db --image_path $images --output_path $out/colmap/sparse --Mapper.num_threads 2 $colmap_fixed"
  mkdir -p "$out"
  report=$work/$name.txt
  python3 "$root/scripts/paired_timing.py" "$runs" "$ramap_cmd" "$colmap_cmd" >"$report"
  awk -v first="$name" -v second="$intrinsics" -f "$root/scripts/paired_ratio.awk" "$report"
done
