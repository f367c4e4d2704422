#!/usr/bin/env bash
# Speed ratios the way they are quoted: `ramap mapper` (its defaults, BA included) against GLOMAP
# (COLMAP 4.1.1's global_mapper) and COLMAP 3.8's mapper, each with its defaults on the same
# database, timed in paired, alternated runs (A B A B ...); the median of the pairs'
# ratios is printed per data set. The peers run on copies of the database made (and, for COLMAP
# 4, upgraded by a warm-up run) before the clock starts.
#
#   scripts/bench_speed_paired.sh [NAME ...]   (default: the five collections)
#
# Settings: RAMAP_INTRINSICS=unknown (default; the databases of build/bench-unknown-intrinsics) or
# known (build/bench, the peers' and ramap's intrinsics fixed), RAMAP_RUNS (default 3),
# RAMAP_BINARY (default build/ramap), RAMAP_PEERS=0 to leave GLOMAP out (else scripts/peers.sh
# builds COLMAP 4.1.1 once, 1-1.5 h; COLMAP 3.8 is Debian's).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
intrinsics=${RAMAP_INTRINSICS:-unknown}
runs=${RAMAP_RUNS:-3}
bench=$root/build/bench
[[ $intrinsics == unknown ]] && bench=$root/build/bench-unknown-intrinsics
names=("$@")
((${#names[@]})) || names=(fountain-P11 Herz-Jesus-P8 templeRing lund_door sceaux_castle)
ramap=${RAMAP_BINARY:-$root/build/ramap}
peer=
[[ ${RAMAP_PEERS:-1} != 0 ]] && peer=$(bash "$root/scripts/peers.sh")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fixed_ramap=() fixed_glomap=() fixed_colmap=()
if [[ $intrinsics == known ]]; then
  fixed_ramap=(--BundleAdjustment.refine_focal_length 0 --BundleAdjustment.refine_principal_point 0
    --BundleAdjustment.refine_extra_params 0)
  for what in focal_length principal_point extra_params; do
    fixed_glomap+=(--GlobalMapper.ba_refine_$what 0)
    fixed_colmap+=(--Mapper.ba_refine_$what 0)
  done
fi

echo "| data set | against | ramap wall (s) | peer wall (s) | peer / ramap (median of pairs) | min-max |"
echo "| --- | --- | --- | --- | --- | --- |"
for name in "${names[@]}"; do
  db=$bench/$name/database.db
  [[ -f $db ]] || { echo "bench_speed_paired: $name: no database, skipped" >&2; continue; }
  images=$bench/$name/images
  ramap_cmd="$ramap mapper --database_path $db --output_path $work/$name/ramap --Mapper.num_threads 2 ${fixed_ramap[*]}"
  mkdir -p "$work/$name/glomap" "$work/$name/colmap"
  cp "$db" "$work/$name/glomap.db" && cp "$db" "$work/$name/colmap.db"
  glomap_cmd="$peer global_mapper --database_path $work/$name/glomap.db --image_path $images --output_path $work/$name/glomap --GlobalMapper.num_threads 2 ${fixed_glomap[*]}"
  colmap_cmd="colmap mapper --database_path $work/$name/colmap.db --image_path $images --output_path $work/$name/colmap --Mapper.num_threads 2 ${fixed_colmap[*]}"
  peer_names=("COLMAP 3.8")
  [[ -n $peer ]] && peer_names=(GLOMAP "COLMAP 3.8")
  for peer_name in "${peer_names[@]}"; do
    peer_cmd=$glomap_cmd
    [[ $peer_name == GLOMAP ]] || peer_cmd=$colmap_cmd
    report=$work/$name.$RANDOM.txt
    python3 "$root/scripts/paired_timing.py" "$runs" "$ramap_cmd" "$peer_cmd" > "$report"
    # The report's rows: "<figure> min median max"; A is ramap, B the peer, the ratio A/B.
    awk -v first="$name" -v second="$peer_name" -f "$root/scripts/paired_ratio.awk" "$report"
  done
done
