#!/usr/bin/env bash
# Drives from both generators: `ramap synthesize` (the scale benchmark's settings, see
# bench_scale.sh) and scripts/drive_generator.py (written apart from it), two seeds each, along
# the KITTI, TUM and EuRoC ground-truth motions in ../shared/data/gt_trajectories, mapped by
# `ramap mapper` with its defaults (RAMAP_MAPPER_ARGS adds options, e.g. "--Mapper.refine 0") and
# scored by `ramap evaluate`. Prints one markdown row per drive: registered, ATE as a share of the
# path, rotation error median, every stage's time, peak memory.
#
#   scripts/bench_drives.sh                        KITTI 00 02 05 06 08, both generators, seeds 1 2
#   scripts/bench_drives.sh drivegen:06:1 ...      GENERATOR:MOTION:SEED[:ALIASED] (MOTION: a KITTI
#                                                  sequence, tum_fr1, tum_fr2, euroc_v101, euroc_v102;
#                                                  ALIASED: share of aliased pairs, 0.03 by default)
#
# Drives are cached under build/bench-drives (RAMAP_DRIVES_DIR); RAMAP_DATA_DIR as elsewhere.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
drives_dir=${RAMAP_DRIVES_DIR:-$root/build/bench-drives}
ramap=${RAMAP_BINARY:-$root/build/ramap}
python=${RAMAP_PYTHON:-/usr/bin/python3}
read -r -a extra_args <<<"${RAMAP_MAPPER_ARGS:-}"
motions=$data_dir/gt_trajectories
[[ -x $ramap ]] || { echo "bench_drives: $ramap not built (run scripts/build.sh)" >&2; exit 1; }
[[ -d $motions ]] || { echo "bench_drives: skipped, no ground-truth motions in $motions" >&2; exit 0; }
runs=("$@")
if ((${#runs[@]} == 0)); then
  for sequence in 00 02 05 06 08; do
    for generator in synthesize drivegen; do
      for seed in 1 2; do runs+=("$generator:$sequence:$seed"); done
    done
  done
fi
mkdir -p "$drives_dir"
source "$root/scripts/datasets/kitti_drive.sh"

# motion -> trajectory file, drive_generator's stride, synthesize's camera
motion_file() {
  case $1 in
    tum_fr1) echo "$motions/tum_rgbd/freiburg1_xyz-groundtruth.txt 3" ;;
    tum_fr2) echo "$motions/tum_rgbd/freiburg2_desk-groundtruth.txt 10" ;;
    euroc_v101) echo "$motions/euroc/V1_01_easy-gt_tum_format.txt 1" ;;
    euroc_v102) echo "$motions/euroc/V1_02_medium-state_groundtruth_estimate0.csv 10" ;;
    *) echo "$motions/kitti_odometry_poses/$1.txt 1" ;;
  esac
}

make_drive() {  # generator motion seed aliased dir
  local generator=$1 motion=$2 seed=$3 aliased=$4 dir=$5 file stride
  read -r file stride <<<"$(motion_file "$motion")"
  [[ -f $file ]] || { echo "bench_drives: no motion file $file" >&2; return 1; }
  if [[ $generator == drivegen ]]; then
    "$python" "$root/scripts/drive_generator.py" --trajectory "$file" --output_path "$dir" \
      --seed "$seed" --stride "$stride" --aliased_ratio "$aliased" >&2
  elif [[ $motion =~ ^[0-9][0-9]$ ]]; then
    local frames
    frames=$(wc -l < "$file")
    synthesize_kitti_drive "$ramap" "$dir" "$file" 0 $((20 * frames)) "$seed" 8 "$aliased" >&2
  else
    echo "bench_drives: ramap synthesize drives follow KITTI motions only ($motion)" >&2
    return 1
  fi
}

rows=()
for run in "${runs[@]}"; do
  IFS=: read -r generator motion seed aliased <<<"$run"
  aliased=${aliased:-0.03}
  dir=$drives_dir/${generator}_${motion}_s${seed}_a${aliased}
  [[ -f $dir/database.db ]] || make_drive "$generator" "$motion" "$seed" "$aliased" "$dir" || continue
  rm -rf "$dir/sparse" "$dir/eval.json"
  if ! "$ramap" mapper --database_path "$dir/database.db" --output_path "$dir/sparse" \
      "${extra_args[@]}" > "$dir/mapper.log" 2>&1; then
    rows+=("$run|$dir|failed")
    continue
  fi
  "$ramap" evaluate --model_path "$dir/sparse/0" --ground_truth "$dir/ground_truth.txt" \
    --ground_truth_format tum --database_path "$dir/database.db" \
    --output_path "$dir/eval.json" > /dev/null
  rows+=("$run|$dir|ok")
done

"$python" - "${rows[@]}" <<'PY'
import json, os, sys
print("| generator | motion | seed | aliased | frames | registered | ATE / path | rotation error median (deg) | relative poses (s) | rotation averaging (s) | translation averaging (s) | bundle adjustment (s) | total (s) | peak RSS (MiB) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
for arg in sys.argv[1:]:
    run, folder, status = arg.split("|")
    generator, motion, seed, *rest = run.split(":")
    aliased = rest[0] if rest else "0.03"
    if status != "ok":
        tail = open(os.path.join(folder, "mapper.log")).read().strip().splitlines()[-1:]
        print(f"| {generator} | {motion} | {seed} | {aliased} | | failed: {tail[0] if tail else ''} | | | | | | | | |")
        continue
    summary = json.load(open(os.path.join(folder, "sparse", "summary.json")))
    evaluation = json.load(open(os.path.join(folder, "eval.json")))
    stages = summary["stage_seconds"]
    print(f"| {generator} | {motion} | {seed} | {aliased} | {summary['num_images']} | "
          f"{summary['num_registered_images']} | {100 * evaluation['ate']['rmse_over_path_length']:.2f}% | "
          f"{evaluation['rotation_error_deg']['median']:.3f} | {stages.get('relative poses', 0):.1f} | "
          f"{stages.get('rotation averaging', 0):.2f} | {stages.get('translation averaging', 0):.1f} | "
          f"{stages.get('bundle adjustment', 0):.1f} | {summary['total_seconds']:.1f} | {summary['peak_rss_mib']:.0f} |")
PY
