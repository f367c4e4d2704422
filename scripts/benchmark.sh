#!/usr/bin/env bash
# COLMAP's BA mapper vs ramap's averaging mapper (with and without --Mapper.refine 1) on the SAME
# COLMAP database of every benchmark data set, in one run, through `ramap compare`, with COLMAP
# 4.1.1's incremental mapper and its global_mapper (GLOMAP) as peers: each mapper is
# timed as a whole process and evaluated against the data set's ground truth (or, without one,
# against COLMAP's model). Then the mapper table of BENCHMARKS.md is rewritten and the figures are
# copied to docs/figures/NAME/.
#
#   scripts/benchmark.sh [NAME ...]            (default: every data set present)
#
# Databases come from scripts/prepare_datasets.sh, which this runs first (cached: a data set whose
# database is complete is not touched again). Intrinsics stay fixed in every mapper, as
# ../shared/data/README.md asks. Settings: RAMAP_DATA_DIR (default ../shared/data), RAMAP_BENCH_DIR
# (default build/bench), RAMAP_PEERS=0 to leave the peers out (else scripts/peers.sh builds them
# once, 1-1.5 h, and caches them; without ../shared/peers they are left out with a note).
#
# RAMAP_INTRINSICS=unknown: the same on databases made as a user without a calibration makes them
# (COLMAP's SIMPLE_RADIAL guess, prior_focal_length 0), every mapper with its defaults (intrinsics
# refined); rewrites the "Unknown intrinsics" table, with each mapper's focal length error.
# RAMAP_BENCHMARKS_FILE: the file whose table is rewritten (default BENCHMARKS.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
intrinsics=${RAMAP_INTRINSICS:-known}
if [[ $intrinsics == unknown ]]; then
  bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench-unknown-intrinsics}
  compare_options=(--Compare.refine_intrinsics 1 --Compare.png_figures 1)
else
  bench_dir=${RAMAP_BENCH_DIR:-$root/build/bench}
  compare_options=(--Compare.png_figures 1)
fi
ramap=${RAMAP_BINARY:-$root/build/ramap}
source "$root/scripts/datasets/list.sh"
[[ -x $ramap ]] || { echo "benchmark: $ramap not built (run scripts/build.sh)" >&2; exit 1; }
RAMAP_INTRINSICS=$intrinsics RAMAP_BENCH_DIR=$bench_dir bash "$root/scripts/prepare_datasets.sh" "$@"
peer_options=()
if [[ ${RAMAP_PEERS:-1} != 0 ]]; then
  peer=$(bash "$root/scripts/peers.sh")
  [[ -n $peer ]] && peer_options=(--peer_colmap "$peer")
fi

ran=()
for entry in "${RAMAP_DATASETS[@]}"; do
  IFS='|' read -r name _ _ _ _ _ _ <<<"$entry"
  if (($# > 0)) && [[ " $* " != *" $name "* ]]; then continue; fi
  dir=$bench_dir/$name
  if [[ ! -f $dir/database.done ]]; then
    echo "benchmark: $name: no database, skipped" >&2
    continue
  fi
  # shellcheck disable=SC1091
  source "$dir/dataset.env"
  gt_options=()
  [[ -n $ground_truth ]] && gt_options=(--ground_truth "$ground_truth" --ground_truth_format "$ground_truth_format")
  echo "benchmark: $name"
  rm -f "$dir/compare/report.json"
  # compare exits non-zero when a mapper failed, after writing the report that says which.
  if ! "$ramap" compare --database_path "$dir/database.db" --image_path "$images" \
    --output_path "$dir/compare" "${gt_options[@]}" "${compare_options[@]}" "${peer_options[@]}" \
    >"$dir/compare.log" 2>&1; then
    if [[ ! -f $dir/compare/report.json ]]; then
      echo "benchmark: $name: ramap compare failed (log: $dir/compare.log)" >&2
      continue
    fi
    echo "benchmark: $name: a mapper failed; its row says so (log: $dir/compare.log)" >&2
  fi
  if [[ $intrinsics == known ]]; then
    mkdir -p "$root/docs/figures/$name"
    cp "$dir"/compare/*.png "$root/docs/figures/$name/"
  fi
  ran+=("$dir")
done

((${#ran[@]})) || { echo "benchmark: nothing ran" >&2; exit 1; }
RAMAP_VERSION=$("$ramap" --version) python3 "$root/scripts/benchmark_table.py" \
  --intrinsics "$intrinsics" "${RAMAP_BENCHMARKS_FILE:-$root/BENCHMARKS.md}" "${ran[@]}"
