#!/usr/bin/env bash
# Fuzzes ramap's readers: builds the libFuzzer harnesses of fuzz/ (clang, AddressSanitizer and
# UBSan) into build-fuzz/ and runs each one for SECONDS (default 20), two at a time, starting from
# its seeds: the hand-written ones in tests/fuzz/<harness>/ and those made here from a small
# synthetic scene by the built ramap (database, models, relative poses, trajectory; nothing binary
# is stored in the repository). Exits non-zero on the first finding, printing the harness's log
# and the input that triggered it.
#   scripts/fuzz.sh [SECONDS] [HARNESS ...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-20}
shift || true
harnesses=("$@")
((${#harnesses[@]})) ||
  harnesses=(database model_bin model_txt ground_truth pose_priors relative_poses g2o)
build=${RAMAP_FUZZ_BUILD_DIR:-$root/build-fuzz}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

exec 9>/tmp/ramap-build.lock
flock 9
CXX=clang++ cmake -S "$root/fuzz" -B "$build" "${generator[@]}" >/dev/null
cmake --build "$build" -j 2
flock -u 9

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Seeds from a scene ramap writes itself, in the harnesses' input formats (fuzz/fuzz_input.h: a
# model's three files separated by "\n@@\n"; the ground-truth harness's first byte picks the format).
make_seeds() {
  local ramap=${RAMAP_BINARY:-$root/build/ramap} scene=$work/scene seeds=$work/seeds
  mkdir -p "$seeds"/{database,model_bin,model_txt,relative_poses,ground_truth}
  if [[ ! -x $ramap ]]; then
    echo "fuzz: $ramap not built; only the hand-written seeds" >&2
    return
  fi
  "$ramap" synthesize --output_path "$scene" --Synthetic.path circle --Synthetic.num_images 5 \
    --Synthetic.num_points 300 --Synthetic.seed 2 >/dev/null
  "$ramap" model_converter --input_path "$scene/ground_truth" --output_path "$scene/text" \
    --output_type TXT >/dev/null
  "$ramap" relative_poses --database_path "$scene/database.db" \
    --output_path "$seeds/relative_poses/synthetic" >/dev/null
  cp "$scene/database.db" "$seeds/database/synthetic.db"
  for generation in 3.10 4; do
    "$ramap" database_converter --database_path "$scene/database.db" \
      --output_path "$seeds/database/synthetic-$generation.db" --Database.generation "$generation" \
      >/dev/null
  done
  for format in bin txt; do
    local folder=$scene/ground_truth
    [[ $format == txt ]] && folder=$scene/text
    { cat "$folder/cameras.$format"; printf '\n@@\n'; cat "$folder/images.$format"
      printf '\n@@\n'; cat "$folder/points3D.$format"; } >"$seeds/model_$format/synthetic"
    # With COLMAP 4's rigs and frames as the fourth and fifth parts.
    { cat "$seeds/model_$format/synthetic"; printf '\n@@\n'; cat "$folder/rigs.$format"
      printf '\n@@\n'; cat "$folder/frames.$format"; } >"$seeds/model_$format/synthetic_rigs"
  done
  { printf '\x00'; cat "$scene/ground_truth.txt"; } >"$seeds/ground_truth/tum"
}
make_seeds
run_one() {
  local name=$1 corpus=$work/$1
  mkdir -p "$corpus" "$work/artifacts"
  for seeds in "$root/tests/fuzz/$name" "$work/seeds/$name"; do
    if [[ -d $seeds ]]; then cp "$seeds"/. "$corpus/" -r; fi
  done
  if "$build/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$work/artifacts/$name-" -print_final_stats=1 "$corpus" >"$work/$name.log" 2>&1; then
    echo "fuzz $name: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/$name.log" |
      grep -o '[0-9]*$') inputs in ${seconds} s, no finding"
  else
    echo "fuzz $name: FINDING"
    # The sanitizer's or libFuzzer's report, without the progress lines before it.
    grep -v '^#[0-9]' "$work/$name.log" | tail -40
    ls "$work/artifacts"
    mkdir -p "$build/findings" && cp "$work/artifacts/$name-"* "$build/findings/" 2>/dev/null || true
    return 1
  fi
}
export -f run_one
export root build work seconds
printf '%s\n' "${harnesses[@]}" | xargs -P 2 -I{} bash -c 'run_one {}'
echo "fuzz: ${#harnesses[@]} harnesses, ${seconds} s each, no finding"
