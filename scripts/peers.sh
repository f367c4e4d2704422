#!/usr/bin/env bash
# Builds the peer mappers once and prints the path of their binary: COLMAP 4.1.1 headless, whose
# `mapper` is COLMAP's incremental mapper and whose `global_mapper` is GLOMAP. The build takes
# 1-1.5 h on 2 cores (../shared/peers/build.sh), so it is cached and reused; it belongs in the
# benchmark scripts' set-up only, never in CI or the tests.
#
#   scripts/peers.sh            -> prints PEERS_DIR/build/src/colmap/exe/colmap (builds it if missing)
#
# Settings: RAMAP_PEERS_SOURCE (default ../shared/peers), RAMAP_PEERS_DIR (default build-peers, kept
# apart from build/ so a clean ramap build keeps it), JOBS (default 2).
# Exits 0 with nothing printed when the peer sources are absent, so callers can skip the peer rows.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source_dir=${RAMAP_PEERS_SOURCE:-$root/../shared/peers}
peers_dir=${RAMAP_PEERS_DIR:-$root/build-peers}
binary=$peers_dir/build/src/colmap/exe/colmap

if [[ -x $binary ]] && "$binary" help >/dev/null 2>&1; then
  echo "$binary"
  exit 0
fi
if [[ ! -f $source_dir/build.sh ]]; then
  echo "peers: no peer sources at $source_dir (set RAMAP_PEERS_SOURCE); peer rows skipped" >&2
  exit 0
fi
echo "peers: building COLMAP 4.1.1 into $peers_dir (1-1.5 h on 2 cores, once; log: $peers_dir/build.log)" >&2
mkdir -p "$peers_dir"
if ! bash "$source_dir/build.sh" "$peers_dir" >"$peers_dir/build.log" 2>&1; then
  echo "peers: the build failed; last lines of $peers_dir/build.log:" >&2
  tail -n 20 "$peers_dir/build.log" >&2
  exit 1
fi
"$binary" help >/dev/null 2>&1 || { echo "peers: $binary does not run" >&2; exit 1; }
echo "$binary"
