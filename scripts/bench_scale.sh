#!/usr/bin/env bash
# How ramap scales with the number of frames: synthetic drives along KITTI odometry ground-truth
# trajectories (../shared/data/gt_trajectories), built by `ramap synthesize` as the scale
# benchmark specifies them (each frame matched with its next 10 and with every frame within 8 m that is
# more than 100 frames away; 3% of the pairs aliased, i.e. verified matches of a relative pose
# 0-40 deg off; 2% outlier matches; landmarks on facades 8 m left and right of the road, seen
# within 40 m; 4-column keypoints), then `ramap mapper` (averaging alone, --Mapper.refine 0
# --Mapper.subset_adjustment 0, unless RAMAP_REFINE=1) and `ramap evaluate` against the drive's
# ground truth.
# Prints one markdown table row per drive (stage times from summary.json, peak memory, ATE as a
# share of the path, rotation error) and the log-log slopes of time and memory against frames.
#
#   scripts/bench_scale.sh                       KITTI 00: 500, 1000, 2000, 4541 frames; KITTI 06
#   scripts/bench_scale.sh 00:500 06:1101 ...    SEQUENCE:FRAMES[:SEED[:LAYOUT]] (FRAMES 0: the
#                                                whole sequence; SEED 1 by default; LAYOUT facades,
#                                                the default, or anywhere: landmarks anywhere in
#                                                view instead of on two facades)
#
# Scenes are cached under build/bench-scale (RAMAP_SCALE_DIR); RAMAP_DATA_DIR as elsewhere;
# RAMAP_THREADS (default 2) is --Mapper.num_threads; RAMAP_REFINE=1 adds bundle adjustment (the
# default a new user gets); RAMAP_MAPPER_ARGS, more mapper options (e.g.
# "--TranslationAveraging.irls_cost_tolerance 1e-3").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
scale_dir=${RAMAP_SCALE_DIR:-$root/build/bench-scale}
ramap=${RAMAP_BINARY:-$root/build/ramap}
threads=${RAMAP_THREADS:-2}
refine=${RAMAP_REFINE:-0}
read -r -a extra_args <<<"${RAMAP_MAPPER_ARGS:-}"
poses_dir=$data_dir/gt_trajectories/kitti_odometry_poses
[[ -x $ramap ]] || { echo "bench_scale: $ramap not built (run scripts/build.sh)" >&2; exit 1; }
[[ -d $poses_dir ]] || { echo "bench_scale: skipped, no KITTI trajectories in $poses_dir" >&2; exit 0; }
runs=("$@")
((${#runs[@]})) || runs=(00:500 00:1000 00:2000 00:4541 06:1101)
mkdir -p "$scale_dir"
source "$root/scripts/datasets/kitti_drive.sh"

rows=()
for run in "${runs[@]}"; do
  IFS=: read -r sequence frames seed layout <<<"$run"
  seed=${seed:-1}
  layout=${layout:-facades}
  facade_distance=8
  [[ $layout == anywhere ]] && facade_distance=0
  # Aliased pairs rotated 0-40 deg off (the synthesize default since 2026-12-05; the
  # scenes cached before drew 12-40 deg and had no seed or layout in their names).
  scene=$scale_dir/kitti${sequence}_${frames}_${layout}_s${seed}_a0-40
  if [[ ! -f $scene/scene.done ]]; then
    rm -rf "$scene"
    # 20 landmarks per frame.
    num_points=$((frames > 0 ? 20 * frames : 20 * $(wc -l < "$poses_dir/$sequence.txt")))
    synthesize_kitti_drive "$ramap" "$scene" "$poses_dir/$sequence.txt" "$frames" "$num_points" \
      "$seed" "$facade_distance" 0.03 >&2
    touch "$scene/scene.done"
  fi
  rm -rf "$scene/sparse" "$scene/eval.json"
  "$ramap" mapper --database_path "$scene/database.db" --output_path "$scene/sparse" \
    --Mapper.refine "$refine" --Mapper.subset_adjustment 0 --Mapper.num_threads "$threads" \
    "${extra_args[@]}" > "$scene/mapper.log"
  "$ramap" evaluate --model_path "$scene/sparse/0" --ground_truth "$scene/ground_truth.txt" \
    --ground_truth_format tum --database_path "$scene/database.db" \
    --output_path "$scene/eval.json" > /dev/null
  rows+=("KITTI $sequence s$seed $layout|$scene")
done

python3 - "${rows[@]}" <<'PY'
import json, math, os, sys
print("| drive | frames | verified pairs | database (MB) | wall (s) | relative poses (s) | rotation averaging (s) | translation averaging (s) | triangulation (s) | peak RSS (MiB) | ATE / path | rotation error median (deg) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
fits = {}
for arg in sys.argv[1:]:
    name, scene = arg.split("|")
    summary = json.load(open(os.path.join(scene, "sparse", "summary.json")))
    evaluation = json.load(open(os.path.join(scene, "eval.json")))
    stages = summary["stage_seconds"]
    frames = summary["num_images"]
    ate_share = evaluation["ate"]["rmse_over_path_length"]
    print(f"| {name} | {frames} | {summary['num_verified_pairs']} | "
          f"{os.path.getsize(os.path.join(scene, 'database.db')) / 1e6:.0f} | "
          f"{summary['total_seconds']:.1f} | {stages.get('relative poses', 0):.1f} | "
          f"{stages.get('rotation averaging', 0):.2f} | {stages.get('translation averaging', 0):.1f} | "
          f"{stages.get('triangulation', 0):.1f} | {summary['peak_rss_mib']:.0f} | "
          f"{100 * ate_share:.2f}% | {evaluation['rotation_error_deg']['median']:.3f} |")
    fits.setdefault(name, []).append((frames, summary["total_seconds"], summary["peak_rss_mib"]))

def slope(points):
    xs = [math.log(p[0]) for p in points]; ys = [math.log(p[1]) for p in points]
    mx = sum(xs) / len(xs); my = sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)

for name, points in fits.items():
    if len(points) < 2:
        continue
    print(f"\n{name}: log-log slope against frames: time {slope([(f, t) for f, t, m in points]):.2f}, "
          f"peak memory {slope([(f, m) for f, t, m in points]):.2f} ({len(points)} drives)")
PY
