#!/usr/bin/env bash
# Whether a change moves the mapper's results: `ramap mapper` (averaging alone and + BA, one
# thread, so that bundle adjustment is reproducible) on every prepared benchmark database, known
# intrinsics (fixed) and unknown, each evaluated against its ground truth at full precision (AUC@1,
# 3, 5, 10, ATE RMSE, rotation error median; sceaux_castle, without ground truth: the md5 of its
# images.bin). Run it before and after a change and diff the two files.
#
#   scripts/reproduce_mapper.sh OUT_FILE      (RAMAP_BINARY: the ramap to run; KINDS: "bench" or
#                                              "bench-unknown-intrinsics" to run one of the two;
#                                              RAMAP_MAPPER_ARGS: more mapper options)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1
ramap=${RAMAP_BINARY:-$root/build/ramap}
read -r -a extra_args <<<"${RAMAP_MAPPER_ARGS:-}"
data_dir=${RAMAP_DATA_DIR:-$root/../shared/data}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
: > "$out"
source "$root/scripts/datasets/list.sh"
for kind in ${KINDS:-bench bench-unknown-intrinsics}; do
  for entry in "${RAMAP_DATASETS[@]}"; do
    IFS='|' read -r name _ _ _ _ gt gt_format <<<"$entry"
    db=$root/build/$kind/$name/database.db
    [[ -f $db ]] || continue
    fixed=()
    [[ $kind == bench ]] && fixed=(--BundleAdjustment.refine_focal_length 0
      --BundleAdjustment.refine_principal_point 0 --BundleAdjustment.refine_extra_params 0)
    for refine in 0 1; do
      run=$work/${kind}_${name}_$refine
      if ! "$ramap" mapper --database_path "$db" --output_path "$run" --Mapper.refine "$refine" \
        --Mapper.num_threads 1 "${fixed[@]}" "${extra_args[@]}" > "$run.log" 2>&1; then
        echo "$kind $name $refine FAILED" >> "$out"
        continue
      fi
      if [[ -z $gt ]]; then
        echo "$kind $name $refine $(md5sum < "$run/0/images.bin")" >> "$out"
        continue
      fi
      "$ramap" evaluate --model_path "$run/0" --ground_truth "$data_dir/$gt" \
        --ground_truth_format "$gt_format" --database_path "$db" --output_path "$run.json" > /dev/null
      python3 - "$run.json" "$kind $name $refine" >> "$out" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
auc = r["relative"]["auc_by_threshold_deg"]
print(sys.argv[2], r["num_registered"], "AUC",
      " ".join("@%s %.6f" % (k, auc[k]) for k in sorted(auc, key=float)),
      "ATE %.9g" % r["ate"]["rmse"], "rot %.9g" % r["rotation_error_deg"]["median"])
PY
    done
  done
done
cat "$out"
