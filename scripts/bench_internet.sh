#!/usr/bin/env bash
# "Internet conditions": ramap, COLMAP 3.8 and GLOMAP (COLMAP 4.1.1's global_mapper) from the same
# images, each with its defaults as a user without a calibration runs it, on the sets
# scripts/make_internet_sets.py builds from ../shared/data (every photo cropped and resized its
# own way, EXIF kept, stripped or wrong, near-duplicates, distractors of another set). Prints one
# Markdown row per set, seed and mapper: registered scene images and distractors, the focal length
# error over the scene's images (median and worst), AUC@3, the time from images to model, and
# ramap's time ratio over each peer on that set.
#
#   scripts/bench_internet.sh [SET ...]        (default: every set of make_internet_sets.py)
#
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench),
# RAMAP_BINARY (default build/ramap), RAMAP_SEEDS (default "1 2"), RAMAP_PEERS=0 to leave GLOMAP
# out (scripts/peers.sh builds it once, 1-1.5 h), RAMAP_COLMAP=0 to leave COLMAP 3.8 out.
# COLMAP's runs are cached per set and seed (their folder is kept; delete it to run again).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/internet
ramap=${RAMAP_BINARY:-$root/build/ramap}
python=${RAMAP_PYTHON:-/usr/bin/python3}  # Debian's, with python3-opencv
seeds=${RAMAP_SEEDS:-1 2}
sets=("$@")
((${#sets[@]})) || sets=(internet_fountain internet_herzjesus internet_temple internet_kitti
  internet_lund_door internet_sceaux)
[[ -d $data_dir ]] || { echo "bench_internet: no data at $data_dir (RAMAP_DATA_DIR); skipped" >&2; exit 0; }
command -v exiv2 >/dev/null && "$python" -c "import cv2" 2>/dev/null ||
  { echo "bench_internet: needs exiv2 and python3-opencv (apt-get install exiv2 python3-opencv)" >&2; exit 2; }
glomap=""
[[ ${RAMAP_PEERS:-1} == 1 ]] && glomap=$("$root/scripts/peers.sh" || true)

seconds_of() {  # runs "$@" with its output in $log; prints its wall time in seconds, or "failed"
  local start end
  start=$(date +%s%N)
  if ! "$@" >"$log" 2>&1; then echo failed; return 0; fi
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'
}

scores() {  # set_dir sparse_dir: the scores' JSON, or {} when the mapper wrote nothing
  if [[ -d $2 ]] && ls "$2"/*/images.bin >/dev/null 2>&1; then
    "$python" "$root/scripts/internet_scores.py" "$1" "$2" "$ramap"
  else
    echo '{}'
  fi
}

# COLMAP's pipeline from images: its defaults (one SIMPLE_RADIAL camera per image, EXIF focal
# length or its guess), exhaustive matching (every set is small enough), then `mapper` or
# `global_mapper`. $1 binary, $2 mapper command, $3 output folder, $4 images. COLMAP 4 renamed the
# GPU switches (--FeatureExtraction.use_gpu, --FeatureMatching.use_gpu).
colmap_pipeline() {
  local binary=$1 mapper=$2 out=$3 images=$4 log
  mkdir -p "$out/sparse"
  local extraction=SiftExtraction matching_section=SiftMatching
  if "$binary" feature_extractor -h 2>&1 | grep -q -- --FeatureExtraction.use_gpu; then
    extraction=FeatureExtraction matching_section=FeatureMatching
  fi
  log=$out/features.log
  local features matching mapping
  features=$(seconds_of "$binary" feature_extractor --database_path "$out/database.db" \
    --image_path "$images" "--$extraction.use_gpu" 0)
  log=$out/matching.log
  matching=$(seconds_of "$binary" exhaustive_matcher --database_path "$out/database.db" \
    "--$matching_section.use_gpu" 0)
  log=$out/mapper.log
  mapping=$(seconds_of "$binary" "$mapper" --database_path "$out/database.db" --image_path "$images" \
    --output_path "$out/sparse")
  [[ $features == failed || $matching == failed || $mapping == failed ]] && { echo failed; return; }
  awk -v a="$features" -v b="$matching" -v c="$mapping" 'BEGIN { printf "%.1f", a + b + c }'
}

echo "| set | seed | mapper | scene registered | distractors in scene / registered | models | focal error median / worst | AUC@3 | rot. err. median (deg) | images to model (s) | ramap's speed-up |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for seed in $seeds; do
  sets_dir=$bench_dir/sets_seed$seed
  missing=()
  for set in "${sets[@]}"; do [[ -d $sets_dir/$set ]] || missing+=("$set"); done
  if ((${#missing[@]})); then
    "$python" "$root/scripts/make_internet_sets.py" "$data_dir" "$sets_dir" --seed "$seed" \
      --sets "$(IFS=,; echo "${missing[*]}")" >&2
  fi
  for set in "${sets[@]}"; do
    set_dir=$sets_dir/$set
    runs=$bench_dir/runs_seed$seed/$set
    mkdir -p "$runs"
    rm -rf "$runs/ramap"
    log=$runs/ramap.log
    ramap_seconds=$(seconds_of "$ramap" reconstruct --image_path "$set_dir/images" \
      --output_path "$runs/ramap")
    declare -A seconds=([ramap]=$ramap_seconds)
    declare -A sparse=([ramap]=$runs/ramap/sparse)
    mappers=(ramap)
    if [[ ${RAMAP_COLMAP:-1} == 1 ]]; then
      if [[ ! -f $runs/colmap38/seconds ]]; then
        rm -rf "$runs/colmap38"
        mkdir -p "$runs/colmap38"
        colmap_pipeline colmap mapper "$runs/colmap38" "$set_dir/images" >"$runs/colmap38/seconds"
      fi
      seconds[colmap38]=$(cat "$runs/colmap38/seconds")
      sparse[colmap38]=$runs/colmap38/sparse
      mappers+=(colmap38)
    fi
    if [[ -n $glomap ]]; then
      if [[ ! -f $runs/glomap/seconds ]]; then
        rm -rf "$runs/glomap"
        mkdir -p "$runs/glomap"
        colmap_pipeline "$glomap" global_mapper "$runs/glomap" "$set_dir/images" >"$runs/glomap/seconds"
      fi
      seconds[glomap]=$(cat "$runs/glomap/seconds")
      sparse[glomap]=$runs/glomap/sparse
      mappers+=(glomap)
    fi
    for mapper in "${mappers[@]}"; do
      "$python" - "$set" "$seed" "$mapper" "${seconds[$mapper]}" "$ramap_seconds" \
        "$(scores "$set_dir" "${sparse[$mapper]}")" <<'PY'
import json, sys
name, seed, mapper, seconds, ramap_seconds, scores = sys.argv[1:7]
s = json.loads(scores)
label = {"ramap": "ramap", "colmap38": "COLMAP 3.8", "glomap": "GLOMAP (COLMAP 4.1.1)"}[mapper]
def pct(v):
    return "-" if v is None else f"{100 * v:.1f}%"
if not s:
    print(f"| {name} | {seed} | {label} | failed | | | | | | {seconds} | |")
    sys.exit()
ratio = ""
if mapper != "ramap" and seconds != "failed" and ramap_seconds != "failed":
    ratio = f"{float(seconds) / float(ramap_seconds):.1f}x"
auc = "-" if s["auc3"] is None else f"{s['auc3']:.1f}"
rot = s.get("rotation_error_median_deg")
print(f"| {name} | {seed} | {label} | {s['scene_registered']} / {s['scene_images']} | "
      f"{s['distractors_in_scene']} / {s['distractors_registered']} of {s['distractors']} | "
      f"{s['num_models']} | {pct(s['focal_error_median'])} / {pct(s['focal_error_max'])} | {auc} | "
      f"{'-' if rot is None else f'{rot:.2f}'} | {seconds} | {ratio} |")
PY
    done
    unset seconds sparse
  done
done
