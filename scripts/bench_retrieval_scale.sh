#!/usr/bin/env bash
# Image retrieval at scale: a synthetic collection of unordered photos (a drive of N frames, named
# photo_kqzb.jpg in random order, SIFT-like descriptors per 3D point with noise per view, ~1000
# keypoints per image) matched again from its descriptors by `ramap matcher` (auto: retrieval),
# with the share of the scene's own pairs (each frame's next 10 and the revisits: the pairs its
# mapper needs) that matching verified, and the time of each step on the machine's cores.
#
#   scripts/bench_retrieval_scale.sh [NUM_IMAGES [NEIGHBOURS ...]]   (default: 5000; 10 20 30)
#
# Settings: RAMAP_SCALE_DIR (default build/bench-scale; the scene is kept there and reused).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ramap=$root/build/ramap
scale_dir=${RAMAP_SCALE_DIR:-$root/build/bench-scale}
num_images=${1:-5000}
shift || true
neighbours=("$@")
((${#neighbours[@]})) || neighbours=(10 20 30)
scene=$scale_dir/photos_loop_${num_images}
if [[ ! -f $scene/scene.done ]]; then
  rm -rf "$scene"
  # A closed drive with KITTI's camera, 20 points per frame on facades 8 m to either side, seen
  # up to 40 m away; pairs: the next 10 frames, and revisits within 8 m over 100 frames apart.
  "$ramap" synthesize --output_path "$scene" --Synthetic.path loop \
    --Synthetic.num_images "$num_images" --Synthetic.num_points $((20 * num_images)) \
    --Synthetic.max_view_distance 40 --Synthetic.facade_distance_m 8 --Synthetic.overlap 10 \
    --Synthetic.loop_radius_m 8 --Synthetic.loop_min_frame_gap 100 \
    --Synthetic.loop_max_angle_deg 180 --Synthetic.camera_model PINHOLE \
    --Synthetic.camera_params 718.856,718.856,607.19,185.2 --Synthetic.width 1241 \
    --Synthetic.height 376 --Synthetic.prior_focal_length 1 --Synthetic.keypoint_columns 4 \
    --Synthetic.photo_names 1 --Synthetic.descriptors 1 >&2
  touch "$scene/scene.done"
fi

echo "| images | neighbours | plan | pairs retrieved | pairs verified | recall of the scene's pairs | of those 1-3 frames apart | retrieval (s) | matching, all of it (s) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for k in "${neighbours[@]}"; do
  db=$scene/matched_k$k.db
  cp "$scene/database.db" "$db"
  "$ramap" matcher --database_path "$db" --Matching.retrieval_num_neighbors "$k" \
    >"$scene/matched_k$k.log" 2>&1
  python3 - "$scene/database.db" "$db" "$scene/matched_k$k.log" "$num_images" "$k" <<'PY'
import re, sqlite3, sys
truth_db, matched_db, log, num_images, k = sys.argv[1:6]
def verified(path):
    return {row[0] for row in sqlite3.connect(path).execute(
        "SELECT pair_id FROM two_view_geometries WHERE rows > 0")}
truth, found = verified(truth_db), verified(matched_db)
text = open(log).read()
plan = re.search(r"matching plan: (\w+) .*?: (\d+) retrieved pairs \(retrieval ([\d.]+) s\)", text)
total = re.search(r"pairs verified, ([\d.]+) s", text)
# Image ids are frame numbers (the photo names are a permutation of them).
near = {p for p in truth if 1 <= (p % 2147483647) - (p // 2147483647) <= 3}
recall = len(truth & found) / max(1, len(truth))
near_recall = len(near & found) / max(1, len(near))
print(f"| {num_images} | {k} | {plan.group(1)} | {plan.group(2)} | {len(found)} | "
      f"{100 * recall:.1f}% of {len(truth)} | {100 * near_recall:.1f}% of {len(near)} | "
      f"{plan.group(3)} | {total.group(1)} |")
PY
  rm -f "$db"
done
