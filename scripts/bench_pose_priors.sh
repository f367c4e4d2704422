#!/usr/bin/env bash
# GPS priors on KITTI 07 (first 160 frames): the ground truth as east-north-up fixes with Gaussian
# noise (RAMAP_GPS_NOISE_M per axis, default 2) and five gross errors (+72 m), written as a prior
# file (--PosePrior.type enu about Karlsruhe), then `ramap mapper` with the priors used in each
# way. Prints one row per variant, averaged over three noise draws: metric ATE after a rigid fit
# (no scale), centre error as written (no fit at all), outliers found, mapper time; and COLMAP's
# mapper on the same database aligned to its priors by `colmap model_aligner` with the same fixes.
#
#   scripts/bench_pose_priors.sh     (the COLMAP database from scripts/prepare_datasets.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}
noise=${RAMAP_GPS_NOISE_M:-2}
ramap=$root/build/ramap
RAMAP_BENCH_DIR=$bench_dir bash "$root/scripts/prepare_datasets.sh" kitti07_first160 >&2
# shellcheck disable=SC1091
source "$bench_dir/kitti07_first160/dataset.env"
out=$bench_dir/prior_alignment
rm -rf "$out" && mkdir -p "$out"

# COLMAP: its mapper's model (prepare_datasets.sh ran it) aligned to its priors by colmap
# model_aligner, robust, with the threshold ramap derives (3 x the 3D deviation of the priors).
colmap_threshold=$(python3 -c "print(3 * 3 ** 0.5 * $noise)")
variants=(
  "COLMAP mapper + colmap model_aligner|colmap"
  "no priors (Sim3 fit for reference)|--Mapper.refine 0 --Mapper.subset_adjustment 0 --PosePrior.align 0"
  "aligned to GPS only|--Mapper.refine 0 --Mapper.subset_adjustment 0 --PosePrior.use_in_translation_averaging 0 --PosePrior.use_in_bundle_adjustment 0"
  "GPS in translation averaging|--Mapper.refine 0 --Mapper.subset_adjustment 0"
  "GPS in TA, BA without GPS|--Mapper.refine 1 --PosePrior.use_in_bundle_adjustment 0"
  "GPS in TA and BA|--Mapper.refine 1"
)
echo "| variant (GPS noise $noise m per axis, 5 gross errors) | metric ATE, rigid fit (m) | centre error as written (m) | outliers found | mapper (s) |"
echo "| --- | --- | --- | --- | --- |"
for entry in "${variants[@]}"; do
  IFS='|' read -r label flags <<<"$entry"
  rows=()
  for seed in 1 2 3; do
    priors=$out/priors_$seed.txt
    python3 - "$ground_truth" "$noise" "$seed" "$priors" <<'PY'
import random, sys
gt, noise, seed, path = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
random.seed(seed)
with open(path, "w") as out:
    for i, line in enumerate(l for l in open(gt) if l.strip()):
        v = [float(x) for x in line.split()]
        east, north, up = v[3], v[11], -v[7]  # KITTI: x right, y down, z forward
        east, north, up = (c + random.gauss(0, noise) for c in (east, north, up))
        if i in (15, 45, 80, 110, 140):
            east, north = east + 60, north - 40
        out.write(f"{i:06d}.png {east:.4f} {north:.4f} {up:.4f}\n")
PY
    model=$out/model_$seed
    start=$(date +%s%N)
    if [[ $flags == colmap ]]; then
      mkdir -p "$model/0"
      colmap model_aligner --input_path "$bench_dir/kitti07_first160/colmap/0" --output_path "$model/0" \
        --ref_images_path "$priors" --ref_is_gps 0 --alignment_type custom --robust_alignment 1 \
        --robust_alignment_max_error "$colmap_threshold" >"$model.log" 2>&1
      end=$(date +%s%N)
      # The mapper's time from prepare_datasets.sh, plus the alignment's.
      start=$((start - $(python3 -c "print(int(float(open('$bench_dir/kitti07_first160/colmap.seconds').read()) * 1e9))")))
      echo '{"prior_outliers": []}' >"$model/summary.json"
    else
      # shellcheck disable=SC2086
      "$ramap" mapper --database_path "$bench_dir/kitti07_first160/database.db" --output_path "$model" \
        --PosePrior.path "$priors" --PosePrior.type enu --PosePrior.origin 49.0113,8.4165,115 \
        --PosePrior.std_x_m "$noise" --PosePrior.std_y_m "$noise" --PosePrior.std_z_m "$noise" \
        $flags >"$model.log" 2>&1
      end=$(date +%s%N)
    fi
    "$ramap" model_converter --input_path "$model/0" --output_path "$model/txt" --output_type TXT >/dev/null
    scale=0
    [[ $label == no\ priors* ]] && scale=1
    "$ramap" evaluate --model_path "$model/0" --ground_truth "$ground_truth" --ground_truth_format kitti \
      --estimate_scale "$scale" --database_path "$bench_dir/kitti07_first160/database.db" \
      --output_path "$model/eval.json" >/dev/null
    rows+=("$(python3 - "$model" "$ground_truth" "$start" "$end" "$label" <<'PY'
import json, math, sys
model, gt, start, end, label = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
truth = []
for line in (l for l in open(gt) if l.strip()):
    v = [float(x) for x in line.split()]
    truth.append((v[3], v[11], -v[7]))
lines = [l for l in open(model + "/txt/images.txt") if not l.startswith("#")]
errors = []
for l in lines[0::2]:
    f = l.split()
    qw, qx, qy, qz, tx, ty, tz = map(float, f[1:8])
    R = [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
         [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
         [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]
    c = [-(R[0][i] * tx + R[1][i] * ty + R[2][i] * tz) for i in range(3)]
    errors.append(math.dist(c, truth[int(f[9][:6])]))
absolute = math.sqrt(sum(e * e for e in errors) / len(errors))
ate = json.load(open(model + "/eval.json"))["ate"]["rmse"]
summary = json.load(open(model + "/summary.json"))
outliers = len(summary.get("prior_outliers", []))
if label.startswith("no priors"):
    absolute = float("nan")
print(f"{ate} {absolute} {outliers} {(end - start) / 1e9}")
PY
)")
  done
  printf '%s\n' "${rows[@]}" | python3 -c "
import sys, math
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
mean = lambda k: sum(r[k] for r in rows) / len(rows)
absolute = 'n/a (not aligned)' if math.isnan(mean(1)) else f'{mean(1):.2f}'
found = '-' if math.isnan(mean(1)) or '$flags' == 'colmap' else f'{mean(2):.0f} of 5'
print(f'| $label | {mean(0):.2f} | {absolute} | {found} | {mean(3):.1f} |')"
done
