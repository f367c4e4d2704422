#!/usr/bin/env bash
# Builds one COLMAP database per benchmark data set (CPU SIFT + matching, known intrinsics shared by
# all images), cached: a data set whose database is complete is not touched again.
#
#   scripts/prepare_datasets.sh [NAME ...]      (default: every data set present)
#
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench),
# RAMAP_MAX_IMAGE_SIZE (default 1600, as in ../shared/data/README.md's COLMAP timings),
# RAMAP_INTRINSICS=unknown for databases as a user without a calibration makes them (COLMAP's
# defaults: one SIMPLE_RADIAL camera, focal length 1.2 x the longest side, prior_focal_length 0;
# default bench folder build/bench-unknown-intrinsics).
#
# Known intrinsics reuse the unknown-intrinsics database of the same data set when it is cached
# (RAMAP_FEATURES_FROM, default build/bench-unknown-intrinsics): SIFT features and raw matches do
# not depend on the intrinsics, so only the camera is set and the two-view geometries are verified
# again (COLMAP's matcher verifies pairs that have matches but no geometry: seconds, not the
# 3-20 minutes of extraction and matching). dataset.env records which way a database was made.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
intrinsics=${RAMAP_INTRINSICS:-known}
if [[ $intrinsics == unknown ]]; then
  bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench-unknown-intrinsics}
else
  bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}
fi
max_image_size=${RAMAP_MAX_IMAGE_SIZE:-1600}
features_from=${RAMAP_FEATURES_FROM:-$root/build/bench-unknown-intrinsics}
source "$root/scripts/datasets/list.sh"

if [[ ! -d $data_dir ]]; then
  echo "prepare_datasets: no shared data at $data_dir (set RAMAP_DATA_DIR); nothing to do" >&2
  exit 0
fi

for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images model params matcher gt gt_format <<<"$entry"
  if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
  if [[ ! -d $data_dir/$images ]]; then
    echo "prepare_datasets: $name: $data_dir/$images missing, skipped" >&2
    continue
  fi
  out=$bench_dir/$name
  if [[ -f $out/database.done ]]; then
    echo "prepare_datasets: $name: cached in $out"
    continue
  fi
  rm -rf "$out" && mkdir -p "$out/images"
  # Links to the image files only (templeRing's folder also holds text files).
  find "$data_dir/$images" -maxdepth 1 -type f \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' \) \
    -exec ln -s {} "$out/images/" \;
  start=$(date +%s%N)
  source_db=$features_from/$name/database.db
  if [[ $intrinsics == known && -f $features_from/$name/database.done ]]; then
    made_from="features and matches of $source_db, two-view geometries verified again"
    cp "$source_db" "$out/database.db"
    python3 "$root/scripts/datasets/set_camera.py" "$out/database.db" "$model" "$params"
  else
    made_from="feature extraction and matching"
    camera=(--ImageReader.camera_model "$model" --ImageReader.camera_params "$params")
    [[ $intrinsics == unknown ]] && camera=(--ImageReader.camera_model SIMPLE_RADIAL)
    colmap feature_extractor --database_path "$out/database.db" --image_path "$out/images" \
      --ImageReader.single_camera 1 "${camera[@]}" \
      --SiftExtraction.use_gpu 0 --SiftExtraction.max_image_size "$max_image_size" > "$out/extract.log" 2>&1
  fi
  colmap "${matcher}_matcher" --database_path "$out/database.db" --SiftMatching.use_gpu 0 > "$out/match.log" 2>&1
  end=$(date +%s%N)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
  cat > "$out/dataset.env" <<ENV
name=$name
images=$out/images
camera_model=$model
camera_params=$params
intrinsics=$intrinsics
matcher=$matcher
ground_truth=${gt:+$data_dir/$gt}
ground_truth_format=$gt_format
features_and_matching_seconds=$seconds
made_from="$made_from"
ENV
  touch "$out/database.done"
  echo "prepare_datasets: $name: database built in $seconds s"
done
