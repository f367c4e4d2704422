#!/usr/bin/env bash
# The report screenshots in docs/figures, taken by the browser test (tests/browser/report_test.mjs)
# on the reports a user would open:
#   - report_templeRing_compare.png: `ramap compare` on templeRing's benchmark database with every
#     mapper (COLMAP 3.8, COLMAP 4.1.1 and GLOMAP when scripts/peers.sh has built them, ramap,
#     ramap+BA) against the Middlebury ground truth (scripts/prepare_datasets.sh makes the database);
#   - report_drive4541_mapper.png: `ramap mapper` (defaults, with BA) on the 4541-frame synthetic
#     KITTI 00 drive of scripts/bench_scale.sh.
# Prints each report's size; the browser test prints the time it took to open and draw.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ramap=${RAMAP_BINARY:-$root/build/ramap}
work=${RAMAP_SCREENSHOT_DIR:-$root/build/report-screenshots}
figures=$root/docs/figures
mkdir -p "$work" "$figures"
reports=()

temple=$root/build/bench/templeRing
if [[ -f $temple/database.done ]]; then
  # shellcheck disable=SC1091
  source "$temple/dataset.env"
  peer_options=()
  peer=$(bash "$root/scripts/peers.sh" 2>/dev/null || true)
  [[ -n $peer ]] && peer_options=(--peer_colmap "$peer")
  rm -rf "$work/templeRing"
  "$ramap" compare --database_path "$temple/database.db" --image_path "$images" \
    --output_path "$work/templeRing" --ground_truth "$ground_truth" \
    --ground_truth_format "$ground_truth_format" "${peer_options[@]}" >"$work/templeRing.log" 2>&1 ||
    echo "report_screenshots: a mapper failed on templeRing; its row says so" >&2
  reports+=("$work/templeRing/report.html=$figures/report_templeRing_compare.png")
else
  echo "report_screenshots: no templeRing database (scripts/prepare_datasets.sh templeRing)" >&2
fi

drive=$root/build/bench-scale/kitti00_4541_facades_s1_a0-40
[[ -f $drive/scene.done ]] || bash "$root/scripts/bench_scale.sh" 00:4541 >/dev/null
rm -rf "$work/drive4541"
"$ramap" mapper --database_path "$drive/database.db" --output_path "$work/drive4541" >"$work/drive4541.log"
reports+=("$work/drive4541/report.html=$figures/report_drive4541_mapper.png")

for report in "${reports[@]}"; do
  file=${report%%=*}
  echo "report_screenshots: $file: $(du -h "$file" | cut -f1)"
done
node "$root/tests/browser/report_test.mjs" "${reports[@]}"
