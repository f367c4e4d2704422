#!/usr/bin/env bash
# Configures and builds ramap into ./build (Release). Builds are serialised with a lock file so that
# two builds never share the machine's two cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build_dir=${RAMAP_BUILD_DIR:-$root/build}
jobs=${RAMAP_BUILD_JOBS:-2}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
exec 9>/tmp/ramap-build.lock
flock 9
if [[ ! -f $build_dir/CMakeCache.txt ]]; then
  cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
fi
cmake --build "$build_dir" -j "$jobs"
