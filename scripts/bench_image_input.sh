#!/usr/bin/env bash
# From images to a model, timed end to end on the same images: COLMAP (feature_extractor + matcher
# + mapper, CPU) vs `ramap reconstruct` with ORB and SIFT, with and without bundle adjustment.
# Each result is evaluated against the ground truth with `ramap evaluate`; the table is printed.
#
#   scripts/bench_image_input.sh [NAME ...]     (default: templeRing kitti07_first160)
#
# RAMAP_INTRINSICS=known (default): one PINHOLE camera with the data set's intrinsics, fixed in
# COLMAP's mapper; ramap with --FeatureExtraction.max_num_features RAMAP_MAX_NUM_FEATURES.
# RAMAP_INTRINSICS=unknown: as a user without a calibration runs them, one camera per data set and
# nothing else: COLMAP's defaults (SIMPLE_RADIAL, focal guessed, refined by its mapper) and
# ramap's defaults (`ramap reconstruct --image_path --output_path`, + the fast options); the table
# gains the focal length error against the calibration.
# RAMAP_INTRINSICS=given: as a user with a calibrated camera runs them, the data set's camera
# model and parameters given and nothing else: one camera per image, each tool's defaults (COLMAP's
# mapper refines every focal length), ramap with its defaults only; the focal length column gives
# the written focal length furthest from the calibration.
# COLMAP matches as its documentation advises for the data set (exhaustive, or sequential for
# kitti07_first160); ramap chooses its own plan (--Matching.mode auto). The last column splits
# each run's time into feature extraction, matching and the rest (mapper, loop closure).
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench),
# RAMAP_BINARY (default build/ramap),
# RAMAP_MAX_IMAGE_SIZE (COLMAP's SIFT, default 1600, ramap's default too),
# RAMAP_MAX_NUM_FEATURES (ramap with known intrinsics, default 4000).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
intrinsics=${RAMAP_INTRINSICS:-known}
[[ $intrinsics == known || $intrinsics == unknown || $intrinsics == given ]] ||
  { echo "bench_image_input: RAMAP_INTRINSICS must be known, unknown or given" >&2; exit 2; }
suffix=""
[[ $intrinsics == known ]] || suffix="-$intrinsics-intrinsics"
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/image_input$suffix
ramap=${RAMAP_BINARY:-$root/build/ramap}
max_image_size=${RAMAP_MAX_IMAGE_SIZE:-1600}
max_num_features=${RAMAP_MAX_NUM_FEATURES:-4000}
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(templeRing kitti07_first160)

seconds_of() {  # runs "$@" with its output in $log, prints its wall time in seconds (or "failed")
  local start end
  start=$(date +%s%N)
  if ! "$@" >"${log:-/dev/null}" 2>&1; then echo failed; return 0; fi
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'
}

row() {  # name variant seconds model database stages (the data set's $params and $camera_model)
  local model=$4 report=$bench_dir/$1/$(echo "$2" | tr -c 'a-zA-Z0-9' _).eval.json
  if [[ ! -f $model/images.bin ]]; then
    echo "| $1 | $2 | failed | | | | | $3 | |"
    return
  fi
  "$ramap" evaluate --model_path "$model" --ground_truth "$data_dir/$gt" \
    --ground_truth_format "$gt_format" --database_path "$5" --output_path "$report" >/dev/null
  python3 - "$report" "$1" "$2" "$3" "$model/cameras.bin" "$params" "$camera_model" \
    "$intrinsics" "$6" <<'PY'
import json, struct, sys
report, name, variant, seconds, cameras, known, known_model, intrinsics, stages = sys.argv[1:10]
r = json.load(open(report))
auc = r["relative"]["auc_by_threshold_deg"]
cells = [name, variant]
if intrinsics != "known":
    # cameras.bin: each camera's first parameter(s) are its focal length(s) (SIMPLE_* and RADIAL:
    # f; PINHOLE, OPENCV and the like: fx, fy); the one furthest from the calibration is given.
    num_params = {0: 3, 1: 4, 2: 4, 3: 5, 4: 8, 5: 8, 6: 12, 7: 5, 8: 4, 9: 5, 10: 12}
    p = [float(v) for v in known.split(",")]
    truth = (p[0] + p[1]) / 2 if known_model in ("PINHOLE", "OPENCV", "FULL_OPENCV") else p[0]
    errors = []
    with open(cameras, "rb") as f:
        for _ in range(struct.unpack("<Q", f.read(8))[0]):
            _, model_id, _, _ = struct.unpack("<iiQQ", f.read(24))
            params = struct.unpack(f"<{num_params[model_id]}d", f.read(8 * num_params[model_id]))
            single = model_id in (0, 2, 3, 8, 9)
            focal = params[0] if single else (params[0] + params[1]) / 2
            errors.append(focal / truth - 1)
    cells.append(f"{100 * max(errors, key=abs):+.2f}%")
cells += [f"{r['num_registered']} / {r['num_images']}", f"{100 * auc['1']:.1f}",
          f"{100 * auc['3']:.1f}", f"{100 * auc['5']:.1f}",
          f"{r['rotation_error_deg']['median']:.3f}",
          f"{100 * r['ate']['rmse_over_path_length']:.2f}%", seconds, stages]
print("| " + " | ".join(cells) + " |")
PY
}

focal_header="" && focal_rule=""
[[ $intrinsics == known ]] || { focal_header=" focal error |" && focal_rule=" --- |"; }
echo "| data set | pipeline |$focal_header registered | AUC@1 | AUC@3 | AUC@5 | rot. err. median (deg) | ATE / path | images to model (s) | features / matching / mapper (s) |"
echo "| --- | --- |$focal_rule --- | --- | --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images camera_model params matcher gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  [[ -d $data_dir/$images ]] || { echo "bench_image_input: $name: no images, skipped" >&2; continue; }
  [[ -n $gt ]] || { echo "bench_image_input: $name: no ground truth, skipped" >&2; continue; }
  out=$bench_dir/$name
  rm -rf "$out" && mkdir -p "$out/images" "$out/colmap_sparse"
  find "$data_dir/$images" -maxdepth 1 -type f \( -iname '*.png' -o -iname '*.jpg' \) \
    -exec ln -s {} "$out/images/" \;
  mode=exhaustive
  [[ $matcher == sequential ]] && mode=sequential
  # The camera as the user gives it: the calibration, or nothing (both tools guess).
  colmap_camera=(--ImageReader.single_camera 1)
  colmap_fixed=()
  ramap_camera=(--ImageReader.single_camera 1)
  if [[ $intrinsics == given ]]; then
    colmap_camera=(--ImageReader.camera_model "$camera_model" --ImageReader.camera_params "$params")
    ramap_camera=("${colmap_camera[@]}")
  elif [[ $intrinsics == known ]]; then
    colmap_camera+=(--ImageReader.camera_model "$camera_model" --ImageReader.camera_params "$params")
    colmap_fixed=(--Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_principal_point 0
      --Mapper.ba_refine_extra_params 0)
    ramap_camera+=(--ImageReader.camera_model "$camera_model" --ImageReader.camera_params "$params"
      --FeatureExtraction.max_num_features "$max_num_features"
      --FeatureExtraction.max_image_size "$max_image_size")
  fi
  log=$out/colmap_features.log
  extraction=$(seconds_of colmap feature_extractor --database_path "$out/colmap.db" \
    --image_path "$out/images" "${colmap_camera[@]}" --SiftExtraction.use_gpu 0 \
    --SiftExtraction.max_image_size "$max_image_size")
  log=$out/colmap_matcher.log
  matching=$(seconds_of colmap "${matcher}_matcher" --database_path "$out/colmap.db" \
    --SiftMatching.use_gpu 0)
  log=$out/colmap_mapper.log
  mapping=$(seconds_of colmap mapper --database_path "$out/colmap.db" --image_path "$out/images" \
    --output_path "$out/colmap_sparse" --Mapper.num_threads 2 "${colmap_fixed[@]}")
  seconds=$(awk -v a="$extraction" -v b="$matching" -v c="$mapping" 'BEGIN { printf "%.1f", a + b + c }')
  row "$name" "COLMAP (SIFT, $matcher)" "$seconds" "$out/colmap_sparse/0" "$out/colmap.db" \
    "$extraction / $matching / $mapping"
  # ramap's defaults are SIFT with BA; the others are the options to pass.
  variants=("sift 1" "sift 0" "orb 1" "orb 0")
  [[ $intrinsics == given ]] && variants=("sift 1")
  for variant in "${variants[@]}"; do
    read -r type refine <<<"$variant"
    options=()
    [[ $type == sift ]] || options+=(--FeatureExtraction.type "$type")
    [[ $refine == 1 ]] || options+=(--Mapper.refine 0)
    dir=$out/ramap_${type}_$refine
    # ramap chooses its matching plan itself, as a user's run does.
    log=$dir.log
    seconds=$(seconds_of "$ramap" reconstruct --image_path "$out/images" --output_path "$dir" \
      "${ramap_camera[@]}" "${options[@]}")
    plan=$(grep -o 'matching plan: [a-z]*' "$log" | awk '{print $3}')
    label="ramap reconstruct ($type, ${plan:-$mode}"
    [[ $refine == 1 ]] && label+=", +BA"
    label+=")"
    [[ $variant == "sift 1" ]] && label+=" (defaults)"
    # The first "pairs verified" line is the matching stage; later ones are loop closure's.
    stages=$(awk -v total="$seconds" '
      /^\[ramap\] features:/ { features = $NF == "s" ? $(NF-1) : features }
      /^\[ramap\] matching: .*pairs verified, / && matching == "" { matching = $(NF-1) }
      END { printf "%.1f / %.1f / %.1f", features, matching, total - features - matching }' "$log")
    row "$name" "$label" "$seconds" "$dir/sparse/0" "$dir/database.db" "$stages"
  done
done
