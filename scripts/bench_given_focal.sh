#!/usr/bin/env bash
# A focal length given wrong: `ramap mapper` with its defaults on databases whose camera is marked
# known (prior_focal_length 1) with a wrong focal length, where the given-intrinsics test proves it
# wrong (refine/given_intrinsics_check.h). Herz-Jesus-P8 and fountain-P11 with their true
# calibration scaled by each factor, and lund_door's and sceaux_castle's EXIF focal lengths (the
# databases of build/bench-unknown-intrinsics). One thread, one run each; each row gives AUC@1 and
# AUC@3 against the ground truth (sceaux_castle: COLMAP 3.8's model of the unknown-intrinsics
# benchmark), the focal length written, whether the pipeline averaged again, and the wall time,
# for RAMAP_BINARY_BEFORE (when set) and RAMAP_BINARY.
#
#   scripts/bench_given_focal.sh [FACTOR ...]     (default: 0.6 0.85 0.95 1.1 1.2 1.3 1.6 2)
#
# Settings: RAMAP_BINARY (default build/ramap), RAMAP_BINARY_BEFORE (none by default),
# RAMAP_DATA_DIR (default ../shared/data).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
after=${RAMAP_BINARY:-$root/build/ramap}
before=${RAMAP_BINARY_BEFORE:-}
factors=("$@")
((${#factors[@]})) || factors=(0.6 0.85 0.95 1.1 1.2 1.3 1.6 2)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/datasets/list.sh"

# "AUC@1 AUC@3 focal passes seconds" of one run, or "failed".
run() {
  local ramap=$1 db=$2 truth=$3 format=$4 out=$5
  local start end
  start=$(date +%s.%N)
  if ! "$ramap" mapper --database_path "$db" --output_path "$out" --Mapper.num_threads 1 \
    > "$out.log" 2>&1; then
    echo "failed - - - -"
    return
  fi
  end=$(date +%s.%N)
  "$ramap" evaluate --model_path "$out/0" --ground_truth "$truth" --ground_truth_format "$format" \
    --database_path "$db" --output_path "$out.json" > /dev/null
  local passes=1
  grep -q "averaging again" "$out.log" && passes=2
  python3 - "$out.json" "$out/summary.json" "$start" "$end" "$passes" << 'PY'
import json, sys
auc = json.load(open(sys.argv[1]))["relative"]["auc_by_threshold_deg"]
cameras = json.load(open(sys.argv[2]))["cameras"]
focal = cameras[0]["final_params"][0] if cameras and cameras[0].get("final_params") else float("nan")
print("%.2f %.2f %.1f %s %.2f" % (100 * auc["1"], 100 * auc["3"], focal, sys.argv[5],
                                  float(sys.argv[4]) - float(sys.argv[3])))
PY
}

# The ground truth of data set `name`: "path format".
truth_of() {
  local name=$1 entry n gt format
  for entry in "${RAMAP_DATASETS[@]}"; do
    IFS='|' read -r n _ _ _ _ gt format <<<"$entry"
    [[ $n == "$name" ]] || continue
    if [[ -z $gt ]]; then
      echo "$root/build/bench-unknown-intrinsics/$name/compare/colmap/0 colmap"
    else
      echo "$data_dir/$gt $format"
    fi
  done
}

# A copy of `source_db` whose cameras are marked known with their focal length times `factor`.
scaled_database() {
  local source_db=$1 factor=$2 db=$3
  cp "$source_db" "$db"
  python3 - "$db" "$factor" << 'PY'
import sqlite3, struct, sys
db = sqlite3.connect(sys.argv[1])
factor = float(sys.argv[2])
for camera_id, model, blob in list(db.execute("SELECT camera_id, model, params FROM cameras")):
    params = list(struct.unpack("%dd" % (len(blob) // 8), blob))
    num_focal = 2 if model in (1, 4, 5, 6) else 1  # PINHOLE, OPENCV, OPENCV_FISHEYE, FULL_OPENCV
    for k in range(num_focal):
        params[k] *= factor
    db.execute("UPDATE cameras SET params = ?, prior_focal_length = 1 WHERE camera_id = ?",
               (struct.pack("%dd" % len(params), *params), camera_id))
db.commit()
PY
}

cases=()
for name in Herz-Jesus-P8 fountain-P11; do
  source_db=$root/build/bench/$name/database.db
  [[ -f $source_db ]] || { echo "bench_given_focal: $name: no database, skipped" >&2; continue; }
  for factor in "${factors[@]}"; do
    db=$work/${name}_$factor.db
    scaled_database "$source_db" "$factor" "$db"
    cases+=("$name|$name, focal length x $factor|$db")
  done
done
for name in lund_door sceaux_castle; do
  db=$root/build/bench-unknown-intrinsics/$name/database.db
  [[ -f $db ]] || { echo "bench_given_focal: $name: no database, skipped" >&2; continue; }
  cases+=("$name|$name, EXIF focal length|$db")
done

header="| database |"
rule="| --- |"
binaries=()
[[ -n $before ]] && binaries+=("before:$before")
binaries+=("after:$after")
for entry in "${binaries[@]}"; do
  label=${entry%%:*}
  header+=" AUC@1 $label | AUC@3 $label | focal $label (px) | passes $label | seconds $label |"
  rule+=" --- | --- | --- | --- | --- |"
done
echo "$header"
echo "$rule"
for entry in "${cases[@]}"; do
  IFS='|' read -r name label db <<<"$entry"
  read -r truth format <<<"$(truth_of "$name")"
  row="| $label |"
  for binary in "${binaries[@]}"; do
    tag=${binary%%:*}
    read -r auc1 auc3 focal passes seconds <<<"$(run "${binary#*:}" "$db" "$truth" "$format" \
      "$work/out_${tag}_$RANDOM")"
    row+=" $auc1 | $auc3 | $focal | $passes | $seconds |"
  done
  echo "$row"
done
