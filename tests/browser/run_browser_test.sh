#!/usr/bin/env bash
# The browser test (ctest browser_report): makes the reports a user would open, then checks them
# in Debian's Chromium (report_test.mjs): `ramap mapper` on the bundled default scene
# (data/default_scene.args) and, where COLMAP is installed, `ramap compare` on a 16-image
# synthetic orbit with ground truth (COLMAP's mapper finds no initial pair in the bundled loop and
# spends 90 s saying so). Exits 77 (skipped, with the reason) without Node.js 20 or later,
# Chromium or playwright-core.
#
#   run_browser_test.sh RAMAP_BINARY WORK_DIR [SCREENSHOT_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
ramap=$1
work=$2
shots=${3:-$work}
chromium=${RAMAP_CHROMIUM:-/usr/bin/chromium}
if ! command -v node >/dev/null; then echo "browser test skipped: no node (apt-get install nodejs)"; exit 77; fi
if (( $(node -p 'process.versions.node.split(".")[0]') < 20 )); then
  echo "browser test skipped: playwright-core needs Node.js 20 or later, this is $(node --version)"; exit 77
fi
if [[ ! -x $chromium ]]; then echo "browser test skipped: no Chromium at $chromium (apt-get install chromium)"; exit 77; fi
if [[ ! -d $here/node_modules/playwright-core ]]; then
  echo "browser test skipped: playwright-core is not installed (npm ci --prefix tests/browser)"; exit 77
fi

rm -rf "$work"
mkdir -p "$work" "$shots"
# shellcheck disable=SC2046
"$ramap" synthesize --output_path "$work/default" $(grep -v '^#' "$root/data/default_scene.args") >/dev/null
"$ramap" mapper --database_path "$work/default/database.db" --output_path "$work/default/sparse" >/dev/null
reports=("$work/default/sparse/report.html=$shots/report_mapper_default.png")
if command -v colmap >/dev/null; then
  "$ramap" synthesize --output_path "$work/orbit" --Synthetic.path circle --Synthetic.num_images 16 \
    --Synthetic.num_points 1500 --Synthetic.pixel_noise 0.5 --Synthetic.seed 2 >/dev/null
  "$ramap" compare --database_path "$work/orbit/database.db" --output_path "$work/orbit/compare" \
    --ground_truth "$work/orbit/ground_truth" --ground_truth_format colmap >"$work/orbit/compare.log" 2>&1 ||
    { cat "$work/orbit/compare.log"; exit 1; }
  reports+=("$work/orbit/compare/report.html=$shots/report_compare_orbit.png")
else
  echo "browser test: no colmap on the PATH: the compare report is not tested"
fi
node "$here/report_test.mjs" "${reports[@]}"
