#!/usr/bin/env bash
# The interop table: COLMAP databases of every generation, made by the real programs where they are
# here and by ramap from COLMAP's schema otherwise, each
#   - mapped by `ramap mapper` (known intrinsics, fixed), AUC@3 against the ground truth;
#   - matched again by `ramap matcher` in place (its generation kept), then mapped by COLMAP 4.1.1;
# and ramap's model (rigs.bin and frames.bin beside it) read by COLMAP 3.8 and COLMAP 4.1.1.
#
#   scripts/interop.sh [NAME ...]     (default: Herz-Jesus-P8)
#
# The databases of one data set share their features, except the one COLMAP 4.1.1 extracts itself:
#   3.8      COLMAP 3.8's feature_extractor + exhaustive_matcher (the reference);
#   4 (upgraded)  a copy COLMAP 4.1.1 opened (its exhaustive_matcher adds its tables, keeps the rows);
#   4 (created)   COLMAP 4.1.1's feature_importer + matches_importer --match_type inliers, fed the
#                 3.8 database's keypoints, descriptors and verified matches;
#   4 (ramap), 3.10 (ramap)  `ramap database_converter` of the 3.8 one;
#   4 (own features)  COLMAP 4.1.1's own feature_extractor + exhaustive_matcher.
# Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR (default build/bench).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}/interop
ramap=$root/build/ramap
colmap4=$(bash "$root/scripts/peers.sh")
[[ -x ${colmap4:-} ]] || { echo "interop: needs COLMAP 4.1.1 (scripts/peers.sh)" >&2; exit 1; }
command -v colmap >/dev/null || { echo "interop: needs COLMAP 3.8 (scripts/install-deps.sh)" >&2; exit 1; }
source "$root/scripts/datasets/list.sh"
names=("$@")
((${#names[@]})) || names=(Herz-Jesus-P8)

auc3() {  # model database -> "registered, AUC@3"
  "$ramap" evaluate --model_path "$1" --ground_truth "$data_dir/$gt" \
    --ground_truth_format "$gt_format" --database_path "$2" --output_path "$1.eval.json" \
    >/dev/null 2>&1 || { echo "not evaluated"; return; }
  python3 -c "import json,sys;r=json.load(open(sys.argv[1]));print(f\"{r['num_registered']}/{r['num_images']}, {100*r['relative']['auc_by_threshold_deg']['3']:.1f}\")" "$1.eval.json"
}

schema_of() { "$ramap" database_info --database_path "$1" 2>&1 | sed -n 's/^  schema: *//p'; }

# The 3.8 database's features as COLMAP's import files: NAME.txt (x y scale orientation and 128
# descriptor values per keypoint) and its verified matches as a match list.
export_features() {
  python3 - "$1" "$2" <<'PY'
import math, os, sqlite3, struct, sys
db = sqlite3.connect(sys.argv[1]); out = sys.argv[2]
os.makedirs(f"{out}/features", exist_ok=True)
names = dict(db.execute("SELECT image_id, name FROM images"))
for image_id, rows, cols, data in db.execute("SELECT image_id, rows, cols, data FROM keypoints"):
    k = struct.unpack(f"<{rows * cols}f", data)
    (drows, dcols, ddata), = db.execute("SELECT rows, cols, data FROM descriptors WHERE image_id = ?", (image_id,))
    path = f"{out}/features/{names[image_id]}.txt"
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(f"{rows} 128\n")
        for r in range(rows):
            x, y = k[r * cols], k[r * cols + 1]
            a11, a21 = (k[r * cols + 2], k[r * cols + 4]) if cols == 6 else (1.0, 0.0)
            scale, angle = math.hypot(a11, a21), math.atan2(a21, a11)
            d = ddata[r * 128:(r + 1) * 128]
            f.write(f"{x!r} {y!r} {scale!r} {angle!r} " + " ".join(map(str, d)) + "\n")
with open(f"{out}/matches.txt", "w") as f:
    for pair_id, rows, data in db.execute("SELECT pair_id, rows, data FROM two_view_geometries WHERE rows > 0"):
        i, j = divmod(pair_id, 2147483647)
        m = struct.unpack(f"<{2 * rows}I", data)
        f.write(f"{names[i]} {names[j]}\n" + "".join(f"{m[2*k]} {m[2*k+1]}\n" for k in range(rows)) + "\n")
PY
}

echo "| data set | database | made by | schema read | ramap mapper: registered, AUC@3 | after ramap matcher: schema | COLMAP 4.1.1 mapper on it: registered, AUC@3 |"
echo "| --- | --- | --- | --- | --- | --- | --- |"
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name images camera_model params _ gt gt_format <<<"$entry"
  [[ " ${names[*]} " == *" $name "* ]] || continue
  work=$bench_dir/$name
  rm -rf "$work" && mkdir -p "$work"
  img=$data_dir/$images
  sift=(--ImageReader.single_camera 1 --ImageReader.camera_model "$camera_model"
        --ImageReader.camera_params "$params")
  colmap feature_extractor --database_path "$work/38.db" --image_path "$img" "${sift[@]}" \
    --SiftExtraction.use_gpu 0 --SiftExtraction.max_image_size 1600 >"$work/log" 2>&1
  colmap exhaustive_matcher --database_path "$work/38.db" --SiftMatching.use_gpu 0 >>"$work/log" 2>&1
  declare -A made_by=([38]="COLMAP 3.8")
  order=(38)
  cp "$work/38.db" "$work/4-upgraded.db"
  "$colmap4" exhaustive_matcher --database_path "$work/4-upgraded.db" \
    --FeatureMatching.use_gpu 0 >>"$work/log" 2>&1
  made_by[4-upgraded]="COLMAP 3.8, then opened by COLMAP 4.1.1"; order+=(4-upgraded)
  export_features "$work/38.db" "$work/import"
  "$colmap4" feature_importer --database_path "$work/4-created.db" --image_path "$img" \
    --import_path "$work/import/features" "${sift[@]}" >>"$work/log" 2>&1
  "$colmap4" matches_importer --database_path "$work/4-created.db" \
    --match_list_path "$work/import/matches.txt" --match_type inliers >>"$work/log" 2>&1
  made_by[4-created]="COLMAP 4.1.1 (feature_importer, matches_importer)"; order+=(4-created)
  for generation in 4 3.10; do
    "$ramap" database_converter --database_path "$work/38.db" \
      --output_path "$work/$generation-ramap.db" --Database.generation "$generation" >/dev/null
    made_by[$generation-ramap]="ramap database_converter (COLMAP's schema)"; order+=("$generation-ramap")
  done
  "$colmap4" feature_extractor --database_path "$work/4-own.db" --image_path "$img" "${sift[@]}" \
    --FeatureExtraction.use_gpu 0 --FeatureExtraction.max_image_size 1600 >>"$work/log" 2>&1
  "$colmap4" exhaustive_matcher --database_path "$work/4-own.db" --FeatureMatching.use_gpu 0 \
    >>"$work/log" 2>&1
  made_by[4-own]="COLMAP 4.1.1 (its own features)"; order+=(4-own)

  for db in "${order[@]}"; do
    database=$work/$db.db
    "$ramap" mapper --database_path "$database" --output_path "$work/$db.ramap" \
      --BundleAdjustment.refine_focal_length 0 --BundleAdjustment.refine_principal_point 0 \
      --BundleAdjustment.refine_extra_params 0 >"$work/$db.ramap.log" 2>&1 || true
    mapped=$(auc3 "$work/$db.ramap/0" "$database")
    cp "$database" "$work/$db.rematched.db"
    "$ramap" matcher --database_path "$work/$db.rematched.db" >"$work/$db.matcher.log" 2>&1 || true
    rematched_schema=$(schema_of "$work/$db.rematched.db")
    # COLMAP 4 upgrades what it opens: it gets a copy.
    cp "$work/$db.rematched.db" "$work/$db.colmap4.db"
    mkdir -p "$work/$db.colmap4"
    "$colmap4" mapper --database_path "$work/$db.colmap4.db" --image_path "$img" \
      --output_path "$work/$db.colmap4" --Mapper.ba_refine_focal_length 0 \
      --Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0 \
      >"$work/$db.colmap4.log" 2>&1 || true
    by_colmap4="failed (log: $work/$db.colmap4.log)"
    [[ -f $work/$db.colmap4/0/images.bin ]] && by_colmap4=$(auc3 "$work/$db.colmap4/0" "$database")
    echo "| $name | $db | ${made_by[$db]} | $(schema_of "$database") | $mapped | $rematched_schema | $by_colmap4 |"
  done

  # ramap's model of the COLMAP-created 4.x database, read by both COLMAPs.
  model=$work/4-created.ramap/0
  for pair in "COLMAP 3.8|colmap" "COLMAP 4.1.1|$colmap4"; do
    IFS='|' read -r label exe <<<"$pair"
    out=$work/model-read-by-${label// /-}
    rm -rf "$out" && mkdir -p "$out"
    if "$exe" model_converter --input_path "$model" --output_path "$out" --output_type TXT \
      >"$out.log" 2>&1; then
      extra=""
      [[ -f $out/frames.txt ]] && extra=", with $(grep -vc '^#' "$out/frames.txt") frames and $(grep -vc '^#' "$out/rigs.txt") rigs"
      echo "$label reads ramap's model $model: $(grep -vc '^#' "$out/cameras.txt") camera(s), $(($(grep -vc '^#' "$out/images.txt") / 2)) images$extra"
    else
      echo "$label cannot read ramap's model $model (log: $out.log)"
    fi
  done
done
