#!/usr/bin/env bash
# Fuzzes ramap's readers: builds the libFuzzer harnesses of fuzz/ (clang, AddressSanitizer and
# UBSan) into build-fuzz/ and runs each one for SECONDS (default 20), two at a time, starting from
# its seed corpus in tests/fuzz/<harness>/ (copied: the repository is not changed). Exits non-zero
# on the first finding, printing the harness's log and the input that triggered it.
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
run_one() {
  local name=$1 corpus=$work/$1
  mkdir -p "$corpus" "$work/artifacts"
  cp "$root/tests/fuzz/$name/"* "$corpus/"
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
