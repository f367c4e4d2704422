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
# Configure unless a build system was generated: a configure that failed (a missing package) leaves
# a cache but no build.ninja or Makefile, and must run again once the package is installed.
if [[ ! -f $build_dir/build.ninja && ! -f $build_dir/Makefile ]]; then
  cmake -S "$root" -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "$@"
fi
cmake --build "$build_dir" -j "$jobs"
