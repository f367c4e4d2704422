#!/usr/bin/env bash
# The README's first command: install the dependencies, build, and run the main job on the bundled
# default scene.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
