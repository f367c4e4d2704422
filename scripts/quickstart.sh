#!/usr/bin/env bash
# The README's first command: install the dependencies, build, and run the main job on the bundled
# default scene: generate it (COLMAP database + ground truth), map it with `ramap mapper`, and print
# the evaluation of the model against the ground truth.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"

ramap=$root/build/ramap
scene=$root/data/default
rm -rf "$scene"
# shellcheck disable=SC2046
"$ramap" synthesize --output_path "$scene" $(grep -v '^#' "$root/data/default_scene.args")
"$ramap" mapper --database_path "$scene/database.db" --output_path "$scene/sparse"
"$ramap" evaluate --model_path "$scene/sparse/0" --ground_truth "$scene/ground_truth" \
  --ground_truth_format colmap --database_path "$scene/database.db" --output_path "$scene/evaluation.json"
echo
echo "quickstart: COLMAP model in $scene/sparse/0 (open it with: colmap gui --database_path" \
  "$scene/database.db --import_path $scene/sparse/0), evaluation in $scene/evaluation.json," \
  "the run to look at in a browser: $scene/sparse/report.html"
