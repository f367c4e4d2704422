#!/usr/bin/env bash
# Whether a change moves anything ramap produces. Runs every way in, on one thread so that the
# results are exact, and writes one text file per run into OUT_DIR: summary.json key by key (the
# keys that measure time or memory left out), the md5 of every model file, and the evaluation
# against the ground truth where there is one. Run it before and after a change, then
# `diff -r BEFORE AFTER` (or `scripts/reproduce_behaviour.sh --compare BEFORE AFTER`).
#
#   scripts/reproduce_behaviour.sh OUT_DIR [PART ...]
#
# PARTs (all by default):
#   real     `ramap mapper` on every prepared benchmark database (scripts/prepare_datasets.sh):
#            known intrinsics held, known intrinsics under the defaults (the given camera tested),
#            unknown intrinsics; averaging alone and + BA
#   drive    `ramap synthesize` of a KITTI 06 drive (1101 frames, loops within 8 m, 3% aliased
#            pairs; ../shared/data/gt_trajectories) and of the bundled default scene, then
#            `ramap mapper`: keyframe windows, windowed translation averaging joined by loops
#   images   `ramap reconstruct` from images: templeRing (sequential matching, loop closure) and
#            sceaux_castle (the default plan)
#   rig      `ramap mapper` on a COLMAP 4.1.1 database (rigs and frames; tests/data/colmap4)
#   priors   `ramap mapper` with GPS priors (kitti07_first160's ground truth with 2 m noise and
#            five gross errors, one fixed draw)
#   python   `ramap.global_mapping` and `ramap.evaluate` from Python
#
# Settings: RAMAP_BINARY (build/ramap), RAMAP_PYTHON_DIR (build/python), RAMAP_DATA_DIR
# (../shared/data). Parts whose data are absent are skipped with a line saying so.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [[ ${1:-} == --compare ]]; then
  diff -r "$2" "$3" && echo "reproduce_behaviour: identical ($2, $3)"
  exit
fi
out=$1
shift
parts=("$@")
((${#parts[@]})) || parts=(real drive images rig priors python)
ramap=${RAMAP_BINARY:-$root/build/ramap}
python_dir=${RAMAP_PYTHON_DIR:-$root/build/python}
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
fingerprint=$root/scripts/behaviour_fingerprint.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
source "$root/scripts/datasets/list.sh"
source "$root/scripts/datasets/kitti_drive.sh"

skip() { echo "reproduce_behaviour: $*, skipped" | tee -a "$out/skipped.txt" >&2; }

# record NAME RUN_DIR STATUS [GT GT_FORMAT DB]: the run's fingerprint into OUT_DIR/NAME.txt.
record() {
  local name=$1 run=$2 status=$3 gt=${4:-} gt_format=${5:-} db=${6:-}
  local file=$out/$name.txt
  echo "exit $status" > "$file"
  [[ -d $run ]] || return 0
  local summary
  summary=$(find "$run" -name summary.json | sort | head -1)
  [[ -n $summary ]] && python3 "$fingerprint" summary "$summary" "$work" >> "$file"
  python3 "$fingerprint" models "$run" >> "$file"
  if [[ -n $gt && -f $run/0/images.bin || -n $gt && -f $run/sparse/0/images.bin ]]; then
    local model=$run/0
    [[ -d $model ]] || model=$run/sparse/0
    local db_args=()
    [[ -n $db ]] && db_args=(--database_path "$db")
    "$ramap" evaluate --model_path "$model" --ground_truth "$gt" --ground_truth_format "$gt_format" \
      "${db_args[@]}" --output_path "$run.evaluation.json" > /dev/null
    python3 "$fingerprint" evaluation "$run.evaluation.json" "$work" >> "$file"
  fi
}

# map NAME DB [GT GT_FORMAT] -- MAPPER_ARGS...
map() {
  local name=$1 db=$2 gt=$3 gt_format=$4
  shift 5
  local run=$work/$name status=0
  "$ramap" mapper --database_path "$db" --output_path "$run" --Mapper.num_threads 1 "$@" \
    > "$work/$name.log" 2>&1 || status=$?
  record "$name" "$run" "$status" "$gt" "$gt_format" "$db"
}

part_real() {
  local found=0
  for entry in "${RAMAP_DATASETS[@]}"; do
    IFS='|' read -r name _ _ _ _ gt gt_format <<<"$entry"
    [[ -n $gt ]] && gt=$data_dir/$gt
    for variant in held given unknown; do
      local db=$root/build/bench/$name/database.db args=()
      [[ $variant == unknown ]] && db=$root/build/bench-unknown-intrinsics/$name/database.db
      [[ $variant == held ]] && args=(--BundleAdjustment.refine_focal_length 0
        --BundleAdjustment.refine_principal_point 0 --BundleAdjustment.refine_extra_params 0)
      [[ -f $db ]] || continue
      found=1
      for refine in 0 1; do
        map "real_${name}_${variant}_refine$refine" "$db" "$gt" "$gt_format" -- \
          --Mapper.refine "$refine" "${args[@]}"
      done
    done
  done
  ((found)) || skip "real: no prepared databases under build/bench*"
}

part_drive() {
  "$ramap" synthesize --output_path "$work/default_scene" \
    $(grep -v '^#' "$root/data/default_scene.args") > /dev/null
  md5sum < "$work/default_scene/database.db" | sed 's/^/database.db /' > "$out/synthesize_default.txt"
  map drive_default "$work/default_scene/database.db" "$work/default_scene/ground_truth" colmap --
  local poses=$data_dir/gt_trajectories/kitti_odometry_poses/06.txt
  [[ -f $poses ]] || { skip "drive: no $poses"; return; }
  synthesize_kitti_drive "$ramap" "$work/kitti06" "$poses" 1101 22020 1 8 0.03 > /dev/null
  md5sum < "$work/kitti06/database.db" | sed 's/^/database.db /' > "$out/synthesize_kitti06.txt"
  local gt=$work/kitti06/ground_truth
  map drive_kitti06_averaging "$work/kitti06/database.db" "$gt" colmap -- \
    --Mapper.refine 0 --Mapper.subset_adjustment 0
  map drive_kitti06_defaults "$work/kitti06/database.db" "$gt" colmap --
}

# reconstruct NAME IMAGE_FOLDER GT GT_FORMAT -- ARGS...
reconstruct() {
  local name=$1 images=$2 gt=$3 gt_format=$4
  shift 5
  local run=$work/$name status=0
  "$ramap" reconstruct --image_path "$images" --output_path "$run" --Mapper.num_threads 1 \
    --FeatureExtraction.num_threads 1 "$@" > "$work/$name.log" 2>&1 || status=$?
  record "$name" "$run" "$status" "$gt" "$gt_format" "$run/database.db"
  [[ -f $run/database.db ]] && sqlite3 "$run/database.db" \
    "select count(*) from keypoints; select sum(rows) from keypoints; \
     select count(*), sum(rows) from two_view_geometries;" | sed 's/^/database /' >> "$out/$name.txt"
}

part_images() {
  local temple=$data_dir/middlebury_templeRing sceaux=$data_dir/sceaux_castle/images
  if [[ -d $temple ]]; then
    mkdir -p "$work/temple_images"
    find "$temple" -maxdepth 1 -name '*.png' -exec ln -s {} "$work/temple_images/" \;
    reconstruct images_templeRing "$work/temple_images" "$temple/templeR_par.txt" middlebury -- \
      --Matching.mode sequential
  else
    skip "images: no $temple"
  fi
  if [[ -d $sceaux ]]; then
    reconstruct images_sceaux_castle "$sceaux" "" "" --
  else
    skip "images: no $sceaux"
  fi
}

part_rig() {
  local fixture=$root/tests/data/colmap4
  cp "$fixture/database.db" "$work/colmap4.db"
  map rig_colmap4 "$work/colmap4.db" "$fixture/ground_truth" colmap --
}

part_priors() {
  local db=$root/build/bench/kitti07_first160/database.db
  local gt=$data_dir/kitti_3dv_tutorial/kitti07_first160/poses_gt.txt
  [[ -f $db && -f $gt ]] || { skip "priors: no $db or $gt"; return; }
  python3 - "$gt" "$work/priors.txt" <<'PY'
import random, sys
random.seed(1)
with open(sys.argv[2], "w") as out:
    for i, line in enumerate(l for l in open(sys.argv[1]) if l.strip()):
        v = [float(x) for x in line.split()]
        east, north, up = (c + random.gauss(0, 2) for c in (v[3], v[11], -v[7]))
        if i in (15, 45, 80, 110, 140):
            east, north = east + 60, north - 40
        out.write(f"{i:06d}.png {east:.4f} {north:.4f} {up:.4f}\n")
PY
  map priors_kitti07 "$db" "$gt" kitti -- --PosePrior.path "$work/priors.txt" \
    --PosePrior.type enu --PosePrior.origin 49.011,8.4226,110
}

part_python() {
  local db=$root/build/bench-unknown-intrinsics/fountain-P11/database.db
  [[ -f $db ]] || db=$work/default_scene/database.db
  [[ -f $db ]] || { "$ramap" synthesize --output_path "$work/default_scene" \
    $(grep -v '^#' "$root/data/default_scene.args") > /dev/null; db=$work/default_scene/database.db; }
  [[ -d $python_dir/ramap ]] || { skip "python: no module in $python_dir"; return; }
  local run=$work/python status=0
  PYTHONPATH=$python_dir /usr/bin/python3 - "$db" "$run" "$work/python_result.json" <<'PY' || status=$?
import json, sys
import ramap
models = ramap.global_mapping(sys.argv[1], output_path=sys.argv[2],
                              options={"Mapper": {"num_threads": 1}})
result = {"num_models": len(models), "summary": models.summary, "reason": models.reason,
          "images": {image.name: image.cam_from_world.matrix().tolist()
                     for image in models[0].images.values()}}
json.dump(result, open(sys.argv[3], "w"), default=float)
PY
  record python_global_mapping "$run" "$status"
  [[ -f $work/python_result.json ]] &&
    python3 "$fingerprint" evaluation "$work/python_result.json" "$work" >> "$out/python_global_mapping.txt"
}

for part in "${parts[@]}"; do
  case $part in
    real | drive | images | rig | priors | python) "part_$part" ;;
    *) echo "reproduce_behaviour: unknown part '$part' (real drive images rig priors python)" >&2
       exit 2 ;;
  esac
done
echo "reproduce_behaviour: $(ls "$out" | wc -l) files in $out"
